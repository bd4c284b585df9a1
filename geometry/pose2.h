// Planar rigid motions (SE(2)) as the smoother stores them and the estimator hands it the robot's
// motion (estimator/smoother_input.h): a pose is the vector (x, y, theta),
// metres and radians, theta wrapped to (-pi, pi] (common/angle.h), frames x forward, y left,
// angles counter-clockwise (docs/DEVELOPING.md).
//
// The smoother parameterises a pose by these three numbers directly (an update adds to x, y and
// theta and wraps theta), so every Jacobian here is taken with respect to (x, y, theta). What is
// on the manifold is the residual: odometry and pose priors compare poses through the SE(2)
// logarithm, as GTSAM's BetweenFactor<Pose2> and PriorFactor<Pose2> do (Pose2::Logmap,
// gtsam/geometry/Pose2.cpp), so the optimum of a problem is the one GTSAM finds for it.
#pragma once

#include <Eigen/Core>

namespace slammtt {

// a * b: the pose b given in a's frame, expressed in a's parent frame.
Eigen::Vector3d ComposePoses(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// a^-1 * b: the pose b seen from a. Jacobians with respect to a's and b's (x, y, theta).
Eigen::Vector3d PoseBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            Eigen::Matrix3d* jacobian_a = nullptr,
                            Eigen::Matrix3d* jacobian_b = nullptr);

// The SE(2) logarithm of the motion (x, y, theta): the twist (v_x, v_y, omega) whose exponential
// is that motion: omega = theta, v = V(theta)^-1 (x, y) with
// V(theta)^-1 = [a, b; -b, a], a = (theta / 2) cot(theta / 2), b = theta / 2 (a = 1 at 0).
// Jacobian with respect to (x, y, theta). theta must already be wrapped to (-pi, pi].
Eigen::Vector3d PoseLogarithm(const Eigen::Vector3d& motion,
                              Eigen::Matrix3d* jacobian = nullptr);

// The pose moved by the update `delta` (x + dx, y + dy, wrapped theta + dtheta): the smoother's
// retraction by default.
Eigen::Vector3d RetractPose(const Eigen::Vector3d& pose, const Eigen::Vector3d& delta);

// The SE(2) exponential of the twist (v_x, v_y, omega), the inverse of PoseLogarithm: theta =
// omega, (x, y) = V(omega) v with V(omega) = [s, -c; c, s], s = sin(omega) / omega,
// c = (1 - cos(omega)) / omega (V = I at 0). The result's theta is wrapped.
Eigen::Vector3d PoseExponential(const Eigen::Vector3d& twist);

// pose * exp(delta): the update taken in the pose's own frame, GTSAM's Pose2 retraction
// (Pose2::retract through Pose2::Expmap in gtsam 4.3.0 from PyPI:
// Pose2(1, 2, 0.5).retract((0.1, 0.2, 0.3)) = (0.958726, 2.21891, 0.8)). Its Jacobian with
// respect to delta at delta = 0 is RetractionJacobianAtZero(pose(2)).
Eigen::Vector3d RetractPoseExponential(const Eigen::Vector3d& pose, const Eigen::Vector3d& delta);

// d(pose * exp(delta)) / d(delta) at delta = 0 in (x, y, theta): [R(theta), 0; 0, 1].
Eigen::Matrix3d RetractionJacobianAtZero(double theta);

}  // namespace slammtt
