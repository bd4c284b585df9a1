#include "tools/world/robot_driver.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

RobotDriver::RobotDriver(const RobotMotionSpec& spec) : spec_(spec) {
  double end_s = 0.0;
  for (const VelocitySegment& segment : spec_.profile) {
    end_s += segment.duration_s;
    segment_end_us_.push_back(std::llround(end_s * 1e6));
  }
}

VelocityCommand RobotDriver::CommandAt(int64_t time_us, const Pose2D& pose) {
  if (finished_) return VelocityCommand{};
  if (spec_.waypoints.empty()) {
    if (segment_end_us_.empty() || segment_end_us_.back() <= 0) {
      finished_ = true;
      return VelocityCommand{};
    }
    int64_t t = time_us;
    if (t >= segment_end_us_.back()) {
      if (!spec_.loop) {
        finished_ = true;
        return VelocityCommand{};
      }
      t %= segment_end_us_.back();
    }
    const size_t i = static_cast<size_t>(
        std::upper_bound(segment_end_us_.begin(), segment_end_us_.end(), t) -
        segment_end_us_.begin());
    const VelocitySegment& segment = spec_.profile[std::min(i, spec_.profile.size() - 1)];
    return VelocityCommand{segment.linear_mps, segment.angular_radps};
  }

  // Waypoint controller: skip every waypoint already within tolerance (at most one full lap).
  for (size_t guard = 0; guard <= spec_.waypoints.size(); ++guard) {
    const PlanarPoint& target = spec_.waypoints[next_waypoint_];
    if (std::hypot(target.x_m - pose.x_m, target.y_m - pose.y_m) > spec_.waypoint_tolerance_m) {
      break;
    }
    ++next_waypoint_;
    if (next_waypoint_ == spec_.waypoints.size()) {
      if (!spec_.loop) {
        finished_ = true;
        return VelocityCommand{};
      }
      next_waypoint_ = 0;
    }
  }
  const PlanarPoint& target = spec_.waypoints[next_waypoint_];
  const double error =
      WrapAngle(std::atan2(target.y_m - pose.y_m, target.x_m - pose.x_m) - pose.heading_rad);
  VelocityCommand command;
  command.angular_radps = std::clamp(spec_.turn_gain_per_s * error, -spec_.max_angular_radps,
                                     spec_.max_angular_radps);
  command.linear_mps = spec_.speed_mps * std::max(0.0, std::cos(error));
  return command;
}

}  // namespace slammtt
