// Range-bearing observation of a point object by a laser mounted off the robot's axle centre
// (paper section 2.3, eqs. 10-11).
//
// Eq. 11 places the sensor at offset (a forward, b left) in the robot frame:
//   x_v = x + a cos(phi) - b sin(phi),  y_v = y + a sin(phi) + b cos(phi).
// Eq. 10 then predicts range and bearing of a point m = (x_m, y_m) from there:
//   r = |m - v|,  theta = atan2(y_m - y_v, x_m - x_v) - phi   (wrapped to (-pi, pi]).
// The sensor's axes are the robot's turned by the mount's yaw psi (0 in the paper): the sensor's
// heading is phi + psi, and eq. 10's bearing is measured from it,
//   theta = atan2(y_m - y_v, x_m - x_v) - phi - psi.
// Jacobians follow GTSAM's Pose2::range/bearing convention: returned on request, tested
// against numerical differentiation (tests/estimator/models_test.cc).
#pragma once

#include <Eigen/Core>

namespace slammtt {

// Where the laser sits on the robot (paper eq. 11: a, b).
struct SensorMount {
  double forward_m = 0.0;  // a
  double left_m = 0.0;     // b
  double yaw_rad = 0.0;    // psi: the sensor's x axis, CCW from the robot's (a rotated laser)
};

// Eq. 11: the sensor position in the map frame, with its Jacobian wrt the robot pose (2x3).
Eigen::Vector2d SensorPosition(const Eigen::Vector3d& robot_pose, const SensorMount& mount,
                               Eigen::Matrix<double, 2, 3>* jacobian_robot = nullptr);

// Predicted range and bearing (eq. 10). Jacobians wrt the robot pose (2x3) and the point (2x2).
// Precondition: the point is not at the sensor (range > 0); callers skip objects closer than
// kMinPredictedRange_m, where the bearing is undefined.
inline constexpr double kMinPredictedRange_m = 1e-3;
Eigen::Vector2d PredictRangeBearing(const Eigen::Vector3d& robot_pose,
                                    const Eigen::Vector2d& point, const SensorMount& mount,
                                    Eigen::Matrix<double, 2, 3>* jacobian_robot = nullptr,
                                    Eigen::Matrix2d* jacobian_point = nullptr);

// Inverse of eq. 10: the map-frame point seen at (range, bearing), with Jacobians wrt the robot
// pose (2x3) and the measurement (2x2), used to initialise new objects.
Eigen::Vector2d PointFromRangeBearing(const Eigen::Vector3d& robot_pose,
                                      const Eigen::Vector2d& range_bearing,
                                      const SensorMount& mount,
                                      Eigen::Matrix<double, 2, 3>* jacobian_robot = nullptr,
                                      Eigen::Matrix2d* jacobian_measurement = nullptr);

}  // namespace slammtt
