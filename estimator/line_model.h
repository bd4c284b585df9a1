// Observation of a straight static structure (a wall, a furniture side) as an infinite line in
// Hessian normal form, the line landmarks of the EKF state (slam_state.h, line_landmarks.h).
//
// A line landmark is (rho_m, alpha_rad) in the map frame: the points p with
//   p . n(alpha) = rho,  n(alpha) = (cos alpha, sin alpha).
// rho may be negative in the map frame: the pair is a smooth parameterisation everywhere (a line
// through the map origin has rho = 0 and a well-defined alpha), where keeping rho >= 0 would
// flip alpha by pi whenever an update moved rho across 0.
//
// Seen from the sensor at position s (paper eq. 11) with heading phi + psi (the robot's heading
// plus the mount's yaw, range_bearing_model.h), the line is, in the sensor frame (x forward,
// y left; line_feature_t's form),
//   rho_s = rho - s . n(alpha),  alpha_s = alpha - phi - psi,
// brought to rho_s >= 0 as perception gives it (rho_s -> -rho_s, alpha_s -> alpha_s + pi, the
// rows of rho negated). alpha_s is wrapped to (-pi, pi]. This is the line form of Garulli et
// al.'s line-based SLAM ("Mobile robot SLAM for line-based environment representation", CDC
// 2005, eq. 6) with the sensor offset of the paper's eq. 11. Jacobians on request; tested
// against NumericalJacobian (tests/estimator/line_model_test.cc).
//
// Near rho_s = 0 (the line runs through the sensor) the sign choice flips and the line is
// seen edge on: callers skip predictions with |rho_s| < kMinLineDistance_m.
#pragma once

#include <Eigen/Core>

#include "estimator/range_bearing_model.h"

namespace slammtt {

inline constexpr double kMinLineDistance_m = 0.05;

// The line (rho_s, alpha_s) seen from the sensor. Jacobians wrt the robot pose (2x3) and the
// line (rho, alpha) (2x2). `flipped` (optional): set when rho - s . n(alpha) was negative.
Eigen::Vector2d PredictLineObservation(const Eigen::Vector3d& robot_pose,
                                       const Eigen::Vector2d& line, const SensorMount& mount,
                                       Eigen::Matrix<double, 2, 3>* jacobian_robot = nullptr,
                                       Eigen::Matrix2d* jacobian_line = nullptr,
                                       bool* flipped = nullptr);

// Inverse: the map-frame line (rho, alpha) of a line (rho_s, alpha_s) seen from the robot at
// `robot_pose`, alpha wrapped, rho of either sign (no flip in the map frame). Jacobians wrt the
// robot pose (2x3) and the observation (2x2), to initialise a new line landmark.
Eigen::Vector2d LineFromObservation(const Eigen::Vector3d& robot_pose,
                                    const Eigen::Vector2d& observation, const SensorMount& mount,
                                    Eigen::Matrix<double, 2, 3>* jacobian_robot = nullptr,
                                    Eigen::Matrix2d* jacobian_observation = nullptr);

// A point of the sensor frame in the map frame (for the observed extent of a line).
Eigen::Vector2d SensorPointToMap(const Eigen::Vector3d& robot_pose, const SensorMount& mount,
                                 const Eigen::Vector2d& sensor_point);

// Where `point` lies along the map-frame line (rho, alpha): its coordinate along the line's
// direction (-sin alpha, cos alpha) [m].
double PositionAlongLine(const Eigen::Vector2d& line, const Eigen::Vector2d& point);

// The point of the line at coordinate t along it.
Eigen::Vector2d PointOnLine(const Eigen::Vector2d& line, double t);

}  // namespace slammtt
