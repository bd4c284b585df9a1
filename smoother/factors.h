// The smoother's measurement models: one residual function per factor kind, returning the
// residual (prediction minus measurement, angles wrapped to (-pi, pi]) and, on request, its
// Jacobians with respect to the variables' (x, y, theta) or (x, y). These are the functions the
// optimiser calls; tests/smoother/factors_test.cc checks every Jacobian against numerical
// differentiation.
//
// A factor's cost is r^T Lambda r with Lambda its information matrix (inverse covariance);
// the smoother whitens r by the upper Cholesky factor U of Lambda (Lambda = U^T U).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "estimator/range_bearing_model.h"

namespace slammtt {

// Odometry between keyframes i and j: `measured` is pose j in pose i's frame (x, y, theta).
// r = Log(measured^-1 * (x_i^-1 * x_j)) (pose2.h): GTSAM's BetweenFactor<Pose2> error. 3 rows.
Eigen::Vector3d OdometryResidual(const Eigen::Vector3d& pose_i, const Eigen::Vector3d& pose_j,
                                 const Eigen::Vector3d& measured,
                                 Eigen::Matrix3d* jacobian_i = nullptr,
                                 Eigen::Matrix3d* jacobian_j = nullptr);

// Range and bearing of a point landmark from a laser at `mount` on the robot (paper eqs. 10-11,
// estimator/range_bearing_model.h, whose PredictRangeBearing this calls):
// r = (range - measured range, wrap(bearing - measured bearing)). 2 rows. Precondition of the
// model: the point is not at the sensor (range > kMinPredictedRange_m); closer, the bearing is
// undefined and the residual's bearing row and Jacobians are returned as zero.
Eigen::Vector2d RangeBearingResidual(const Eigen::Vector3d& pose, const Eigen::Vector2d& point,
                                     const Eigen::Vector2d& measured_range_bearing,
                                     const SensorMount& mount,
                                     Eigen::Matrix<double, 2, 3>* jacobian_pose = nullptr,
                                     Eigen::Matrix2d* jacobian_point = nullptr);

// The landmark's position in the pose's frame (Victoria Park's LANDMARK lines):
// r = R(theta)^T (m - t) - measured. 2 rows.
Eigen::Vector2d RelativePositionResidual(const Eigen::Vector3d& pose,
                                         const Eigen::Vector2d& point,
                                         const Eigen::Vector2d& measured_position,
                                         Eigen::Matrix<double, 2, 3>* jacobian_pose = nullptr,
                                         Eigen::Matrix2d* jacobian_point = nullptr);

// Prior on a pose: r = Log(measured^-1 * x) (GTSAM's PriorFactor<Pose2> error). 3 rows.
Eigen::Vector3d PosePriorResidual(const Eigen::Vector3d& pose, const Eigen::Vector3d& measured,
                                  Eigen::Matrix3d* jacobian = nullptr);

// Prior on a point: r = m - measured. 2 rows.
Eigen::Vector2d PointPriorResidual(const Eigen::Vector2d& point, const Eigen::Vector2d& measured,
                                   Eigen::Matrix2d* jacobian = nullptr);

// The upper Cholesky factor U (Lambda = U^T U) of an information matrix, or the reason it is not
// one: a non-finite entry, asymmetry beyond 1e-9 relative, or not positive definite (a pivot
// not above 1e-12 times the largest diagonal entry).
template <int kDim>
std::optional<std::string> SquareRootInformation(
    const Eigen::Matrix<double, kDim, kDim>& information, Eigen::Matrix<double, kDim, kDim>* root);

}  // namespace slammtt
