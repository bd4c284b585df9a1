#include "drivers/sim_robot/simulated_robot.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "drivers/sim_robot/world_laser_scene.h"
#include "runtime/bus.h"
#include "runtime/lcm_io.h"
#include "runtime/log.h"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "tools/world/world_messages.h"

namespace slammtt {

namespace {

int64_t WallClockUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

SimulatedRobot::SimulatedRobot(const Scenario& scenario, uint64_t seed,
                               const SimulatedRobotOptions& options, EventLoop* loop)
    : options_(options), loop_(loop), world_(scenario, seed) {
  world_start_us_ = P3dxEmulator::NowUs();
  world_start_utime_ = WallClockUtime();
  options_.laser.scene = std::make_shared<WorldLaserScene>(&world_, &world_mutex_, world_start_us_);
  options_.laser.range_noise_m = scenario.laser.range_noise_m;
  options_.laser.max_range_m = scenario.laser.max_range_m;
  options_.laser.rotation_hz = scenario.laser.rate_hz;
  base_ = std::make_unique<P3dxEmulator>(options_.base);
  laser_ = std::make_unique<rplidar::RplidarEmulatorServer>(options_.laser,
                                                            options_.laser_transport);
  Step();  // the robot stands at the scenario's start before any sample is measured
}

SimulatedRobot::~SimulatedRobot() = default;

RobotTruth SimulatedRobot::robot() const {
  std::lock_guard<std::mutex> lock(world_mutex_);
  return world_.robot();
}

void SimulatedRobot::Step() {
  const int64_t now_us = P3dxEmulator::NowUs();
  const Pose2D encoders = base_->WithModel([now_us](P3dxRobotModel& model) {
    model.AdvanceTo(now_us);
    return Pose2D{model.x_mm() * 1e-3, model.y_mm() * 1e-3, model.heading_rad()};
  });
  std::lock_guard<std::mutex> lock(world_mutex_);
  world_.Advance(now_us - world_start_us_, encoders);
}

void SimulatedRobot::OnLaserScan(const void* data, int size) {
  slammtt_msgs::laser_scan_t scan;
  if (!Decode(data, size, &scan)) {
    if (IsReportable(++stats_.bad_scans)) {
      LogWarning() << "ignored an undecodable LASER_SCAN (" << stats_.bad_scans << " so far)";
    }
    return;
  }
  const std::vector<double> angles(scan.angle_rad.begin(), scan.angle_rad.end());
  std::optional<TruthSnapshot> truth;
  {
    std::lock_guard<std::mutex> lock(world_mutex_);
    truth = world_.TruthAt(scan.utime - world_start_utime_, angles);
  }
  if (!truth) {
    if (IsReportable(++stats_.scans_outside_history)) {
      LogWarning() << "no truth for a LASER_SCAN of utime " << scan.utime
                   << ": outside the world's history (" << stats_.scans_outside_history
                   << " so far)";
    }
    return;
  }
  const slammtt_msgs::ground_truth_t message = ToGroundTruthMessage(*truth, world_start_utime_);
  Bus& bus = loop_->bus();
  const int64_t failed_before = bus.failed_publishes();
  bus.PublishMessage(options_.ground_truth_channel, message);
  if (bus.failed_publishes() == failed_before) ++stats_.truth_published;
}

void SimulatedRobot::Run(const std::function<bool()>& stop_requested) {
  // Both device threads stop and are joined on every way out of here, an exception included.
  struct DeviceThreads {
    explicit DeviceThreads(SimulatedRobot* owner) : robot(owner) {}
    SimulatedRobot* robot;
    std::atomic<bool> stop{false};
    std::thread base;
    ~DeviceThreads() {
      robot->laser_->Stop();
      stop = true;
      if (base.joinable()) base.join();
    }
  } devices{this};
  devices.base = std::thread([this, &devices] {
    try {
      base_->Run([&devices] { return devices.stop.load(); });
    } catch (const std::exception& e) {
      LogError() << "the base emulator stopped: " << e.what();
    }
  });
  laser_->Start();
  Bus& bus = loop_->bus();
  const int subscription = bus.SubscribeBytes(
      options_.laser_scan_channel,
      [this](const std::string&, const void* data, int size) { OnLaserScan(data, size); });
  try {
    // A signal ends the wait early (the SIGINT that stops us); a bus that fails throws.
    while (!stop_requested()) {
      Step();
      loop_->HandleTimeout(options_.step_ms);
    }
  } catch (...) {
    bus.Unsubscribe(subscription);  // no handler left pointing at this robot
    throw;
  }
  bus.Unsubscribe(subscription);
}

}  // namespace slammtt
