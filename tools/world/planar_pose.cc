#include "tools/world/planar_pose.h"

#include <cmath>

namespace slammtt {

Pose2D SensorPoseFromRobot(const Pose2D& robot, double mount_a_m, double mount_b_m,
                           double mount_yaw_rad) {
  const double c = std::cos(robot.heading_rad);
  const double s = std::sin(robot.heading_rad);
  return Pose2D{robot.x_m + mount_a_m * c - mount_b_m * s,
                robot.y_m + mount_a_m * s + mount_b_m * c,
                mount_yaw_rad == 0.0 ? robot.heading_rad
                                     : WrapAngle(robot.heading_rad + mount_yaw_rad)};
}

Pose2D MoveUnicycle(const Pose2D& start, double linear_mps, double angular_radps, double dt_s) {
  const double turn = angular_radps * dt_s;
  Pose2D end;
  if (std::abs(turn) < 1e-12) {
    // Straight (or a turn too small for the arc formula to stay accurate): midpoint heading.
    const double heading = start.heading_rad + 0.5 * turn;
    end.x_m = start.x_m + linear_mps * dt_s * std::cos(heading);
    end.y_m = start.y_m + linear_mps * dt_s * std::sin(heading);
  } else {
    const double radius = linear_mps / angular_radps;
    const double end_heading = start.heading_rad + turn;
    end.x_m = start.x_m + radius * (std::sin(end_heading) - std::sin(start.heading_rad));
    end.y_m = start.y_m - radius * (std::cos(end_heading) - std::cos(start.heading_rad));
  }
  end.heading_rad = WrapAngle(start.heading_rad + turn);
  return end;
}

}  // namespace slammtt
