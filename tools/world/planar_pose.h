// Planar poses and the exact unicycle motion of the synthetic robot.
//
// Frames (docs/DEVELOPING.md): world frame x, y with headings CCW from x; robot frame centred on
// the axle midpoint, x forward, y left; sensor frame offset by the mount (a forward, b left),
// paper eq. 11, and turned by the mount's yaw.
#pragma once

#include "common/angle.h"  // WrapAngle

namespace slammtt {

struct Pose2D {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;  // wrapped to (-pi, pi]
};

// Position of the observation device for a robot pose, paper eq. 11:
//   x_v = x + a cos(phi) - b sin(phi),  y_v = y + a sin(phi) + b cos(phi),
// with the robot's heading plus the mount's yaw psi (0: the laser parallel to the robot's
// axes; a laser turned CCW by psi has its heading phi + psi).
Pose2D SensorPoseFromRobot(const Pose2D& robot, double mount_a_m, double mount_b_m,
                           double mount_yaw_rad = 0.0);

// Exact motion of a unicycle that holds linear speed v and yaw rate w for dt seconds: a
// straight segment when w == 0, otherwise a circular arc of radius v / w. The ground truth of the
// world moves the robot with this; the odometry (paper eq. 1) is only an approximation of it.
Pose2D MoveUnicycle(const Pose2D& start, double linear_mps, double angular_radps, double dt_s);

}  // namespace slammtt
