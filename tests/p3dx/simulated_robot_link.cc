#include "simulated_robot_link.h"

#include <algorithm>
#include <limits>

namespace slammtt {
namespace {

class SimulatedLink : public ByteStream {
 public:
  SimulatedLink(SimulatedRobot* robot, int64_t generation)
      : robot_(robot), generation_(generation) {}

  void Write(const uint8_t* data, size_t size, int /*timeout_ms*/) override {
    CheckPlugged();
    robot_->Sync();
    robot_->model().Receive(data, size, robot_->clock().now_us);
  }

  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override {
    const int64_t deadline = robot_->clock().now_us + static_cast<int64_t>(timeout_ms) * 1000;
    for (;;) {
      CheckPlugged();
      robot_->Sync();
      const size_t n = robot_->TakeArrived(buffer, capacity);
      if (n > 0) return n;
      if (robot_->clock().now_us >= deadline) return 0;
      robot_->clock().now_us = std::min(deadline, std::max(robot_->clock().now_us + 1,
                                                            robot_->NextEventUs()));
    }
  }

  void FlushInput() override {
    CheckPlugged();
    robot_->Sync();
    uint8_t sink[256];
    while (robot_->TakeArrived(sink, sizeof sink) > 0) {
    }
  }
  void SetDtr(bool) override {}
  std::string Describe() const override { return "sim:p3dx"; }

 private:
  void CheckPlugged() const {
    if (robot_->unplugged() || robot_->generation() != generation_) {
      throw LinkError("sim:p3dx: device unplugged");
    }
  }
  SimulatedRobot* robot_;
  int64_t generation_;
};

}  // namespace

SimulatedRobot::SimulatedRobot(const P3dxRobotModelOptions& options, SimulatedClock* clock,
                               double bytes_per_second)
    : model_(options), clock_(clock), bytes_per_second_(bytes_per_second) {
  model_.AdvanceTo(clock_->now_us);
}

std::unique_ptr<ByteStream> SimulatedRobot::Open(const std::string& endpoint, int /*baud*/) {
  ++opens_;
  opened_endpoints.push_back(endpoint);
  if (unplugged_) throw LinkError(endpoint + ": no such device (simulated unplug)");
  return std::make_unique<SimulatedLink>(this, generation_);
}

void SimulatedRobot::Unplug() {
  unplugged_ = true;
  ++generation_;
  in_flight_.clear();
  model_.HostDisconnected();
}

void SimulatedRobot::Plug() { unplugged_ = false; }

void SimulatedRobot::Sync() {
  model_.AdvanceTo(clock_->now_us);
  const std::vector<uint8_t> bytes = model_.TakeOutput();
  if (unplugged_) return;  // sent into a cable that leads nowhere
  const int64_t byte_us =
      bytes_per_second_ > 0 ? static_cast<int64_t>(1e6 / bytes_per_second_) : 0;
  line_free_us_ = std::max(line_free_us_, clock_->now_us);
  for (uint8_t byte : bytes) {
    line_free_us_ += byte_us;
    in_flight_.emplace_back(line_free_us_, byte);
  }
}

size_t SimulatedRobot::TakeArrived(uint8_t* buffer, size_t capacity) {
  size_t n = 0;
  while (n < capacity && !in_flight_.empty() && in_flight_.front().first <= clock_->now_us) {
    buffer[n++] = in_flight_.front().second;
    in_flight_.pop_front();
  }
  return n;
}

int64_t SimulatedRobot::NextEventUs() const {
  int64_t next = model_.NextEventUs();
  if (!in_flight_.empty()) next = std::min(next, in_flight_.front().first);
  return next;
}

void RecordingSink::Publish(const std::string& channel, const void* data, int size) {
  if (channel == "ODOMETRY") {
    slammtt_msgs::odometry_t message;
    if (Decode(data, size, &message)) {
      odometry.push_back(message);
      return;
    }
  } else if (channel == "BASE_STATUS") {
    slammtt_msgs::base_status_t message;
    if (Decode(data, size, &message)) {
      status.push_back(message);
      return;
    }
  }
  ++undecodable;
}

}  // namespace slammtt
