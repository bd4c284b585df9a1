// The robot's commanded motion over time: the scenario's velocity profile, or a deterministic
// waypoint-following controller (RobotMotionSpec documents both).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tools/world/planar_pose.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Unicycle command: forward speed of the axle centre and yaw rate (CCW positive).
struct VelocityCommand {
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

// Commands change only at control ticks, every kRobotControlPeriodUs.
inline constexpr int64_t kRobotControlPeriodUs = 10000;

class RobotDriver {
 public:
  RobotDriver() = default;
  explicit RobotDriver(const RobotMotionSpec& spec);
  // The command to hold from time_us (a control tick, microseconds since the start) to the next
  // tick, for the robot at `pose`. A profile segment takes effect at the first tick at or after
  // its start (segment boundaries are computed in whole microseconds, so durations that are
  // multiples of 10 ms switch exactly). Call with non-decreasing time_us (the waypoint
  // controller remembers the current waypoint).
  VelocityCommand CommandAt(int64_t time_us, const Pose2D& pose);

 private:
  RobotMotionSpec spec_;
  std::vector<int64_t> segment_end_us_;  // cumulative ends of the profile segments
  size_t next_waypoint_ = 0;
  bool finished_ = false;
};

}  // namespace slammtt
