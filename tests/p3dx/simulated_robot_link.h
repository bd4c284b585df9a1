// An emulated P3-DX behind a ByteStream, in simulated time: the driver under test reads and
// writes it exactly as it would a serial port, and every wait in Read() advances the simulated
// clock instead of sleeping. Deterministic: the same calls give the same bytes and times.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/p3dx/p3dx_robot_model.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"

namespace slammtt {

class SimulatedClock : public DriverClock {
 public:
  // Wall time = monotonic time + a fixed epoch offset, so the two are told apart in tests.
  static constexpr int64_t kEpochOffsetUs = 1700000000000000;
  int64_t NowUtime() override { return now_us + kEpochOffsetUs; }
  int64_t NowMonotonicUs() override { return now_us; }
  void SleepUs(int64_t duration_us) override { now_us += duration_us > 0 ? duration_us : 0; }
  int64_t now_us = 1000000;
};

// The robot, the wire and the plug.
class SimulatedRobot {
 public:
  // bytes_per_second: how fast the robot's bytes reach the host (960 at 9600 baud); 0 delivers
  // every packet at once.
  SimulatedRobot(const P3dxRobotModelOptions& options, SimulatedClock* clock,
                 double bytes_per_second = 960.0);

  // The factory a P3dxDriver is given: throws LinkError while unplugged.
  std::unique_ptr<ByteStream> Open(const std::string& endpoint, int baud);
  // Pulls the cable: the open link fails on its next call, new opens fail until Plug().
  void Unplug();
  void Plug();

  // Moves robot time to the clock and queues what the robot sent.
  void Sync();
  // Bytes that have reached the host by now, at most `capacity`.
  size_t TakeArrived(uint8_t* buffer, size_t capacity);
  // Time of the next arrival or robot event, INT64_MAX if none.
  int64_t NextEventUs() const;

  P3dxRobotModel& model() { return model_; }
  SimulatedClock& clock() { return *clock_; }
  bool unplugged() const { return unplugged_; }
  int64_t generation() const { return generation_; }
  int opens() const { return opens_; }
  std::vector<std::string> opened_endpoints;

 private:
  P3dxRobotModel model_;
  SimulatedClock* clock_;
  double bytes_per_second_;
  std::deque<std::pair<int64_t, uint8_t>> in_flight_;  // arrival time, byte
  int64_t line_free_us_ = 0;
  bool unplugged_ = false;
  int64_t generation_ = 0;  // +1 per unplug: a link of an older generation is dead
  int opens_ = 0;
};

// Decodes what the driver publishes.
class RecordingSink : public MessageSink {
 public:
  void Publish(const std::string& channel, const void* data, int size) override;
  std::vector<slammtt_msgs::odometry_t> odometry;
  std::vector<slammtt_msgs::base_status_t> status;
  int undecodable = 0;
};

}  // namespace slammtt
