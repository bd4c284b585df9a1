// One simulated robot behind both device emulators: the P3-DX emulator (drivers/p3dx) takes the
// base driver's commands and integrates its encoder pose; that pose moves the robot of an
// EmulatedRobotWorld (tools/world: the scenario's rooms, people and wheel slip); the RPLIDAR
// emulator (drivers/rplidar) measures every sample in that world from the robot's true pose
// (WorldLaserScene); and for every LASER_SCAN the laser driver publishes, the world's truth at
// that scan's utime goes out as GROUND_TRUTH (the message slammtt-world publishes), so that a
// log of the run can be scored by slammtt-eval.
//
// Threads: the base emulator serves on a thread of its own, the laser emulator on another (its
// samples lock the world), and Run() moves the world every step_ms and answers LASER_SCAN on the
// caller's thread. Clocks: the emulators' monotonic clock drives the world (world time 0 = the
// moment the robot was made); the drivers stamp messages with the wall clock, taken at the same
// moment as the offset between the two. Not deterministic: when the drivers' commands and reads
// arrive depends on the machine's scheduling (the world itself is, given the same calls).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "drivers/p3dx/p3dx_emulator.h"
#include "drivers/rplidar/rplidar_emulator_server.h"
#include "runtime/event_loop.h"
#include "tools/world/emulated_robot_world.h"

namespace slammtt {

struct SimulatedRobotOptions {
  P3dxEmulatorOptions base;  // transport, robot model and faults of the base
  // The laser device; its scene, range noise, maximum range and rotation rate are the
  // scenario's laser (WorldLaserScene, LaserSpec).
  rplidar::RplidarDeviceOptions laser;
  rplidar::EmulatorTransportOptions laser_transport;
  int step_ms = 5;  // how often the world follows the base's encoders
  std::string laser_scan_channel = "LASER_SCAN";
  std::string ground_truth_channel = "GROUND_TRUTH";
};

struct SimulatedRobotStats {
  int64_t truth_published = 0;
  int64_t scans_outside_history = 0;  // a LASER_SCAN whose utime the world no longer holds
  int64_t bad_scans = 0;              // undecodable LASER_SCAN
};

class SimulatedRobot {
 public:
  // Opens both devices' links (throws LinkError when it cannot) and the world
  // (std::invalid_argument for a scenario it refuses). `loop` (and its bus) outlives the robot.
  SimulatedRobot(const Scenario& scenario, uint64_t seed, const SimulatedRobotOptions& options,
                 EventLoop* loop);
  ~SimulatedRobot();
  SimulatedRobot(const SimulatedRobot&) = delete;
  SimulatedRobot& operator=(const SimulatedRobot&) = delete;

  std::string base_endpoint() const { return base_->Endpoint(); }
  std::string laser_endpoint() const { return laser_->endpoint(); }

  // Serves both devices and the truth until `stop_requested()` (asked every step).
  void Run(const std::function<bool()>& stop_requested);

  SimulatedRobotStats stats() const { return stats_; }
  // The robot's true pose now (world frame).
  RobotTruth robot() const;

 private:
  void Step();
  void OnLaserScan(const void* data, int size);

  SimulatedRobotOptions options_;
  EventLoop* loop_;
  mutable std::mutex world_mutex_;
  EmulatedRobotWorld world_;
  int64_t world_start_us_ = 0;     // monotonic clock at world time 0
  int64_t world_start_utime_ = 0;  // wall clock (utime) at world time 0
  std::unique_ptr<P3dxEmulator> base_;
  std::unique_ptr<rplidar::RplidarEmulatorServer> laser_;
  SimulatedRobotStats stats_;
};

}  // namespace slammtt
