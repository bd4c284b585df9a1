#include "smoother/factors.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "common/angle.h"
#include "geometry/pose2.h"

namespace slammtt {

Eigen::Vector3d OdometryResidual(const Eigen::Vector3d& pose_i, const Eigen::Vector3d& pose_j,
                                 const Eigen::Vector3d& measured, Eigen::Matrix3d* jacobian_i,
                                 Eigen::Matrix3d* jacobian_j) {
  Eigen::Matrix3d between_i;
  Eigen::Matrix3d between_j;
  const Eigen::Vector3d relative = PoseBetween(pose_i, pose_j, &between_i, &between_j);
  Eigen::Matrix3d error_relative;
  const Eigen::Vector3d error = PoseBetween(measured, relative, nullptr, &error_relative);
  Eigen::Matrix3d log_error;
  const Eigen::Vector3d residual = PoseLogarithm(error, &log_error);
  const Eigen::Matrix3d chain = log_error * error_relative;
  if (jacobian_i != nullptr) *jacobian_i = chain * between_i;
  if (jacobian_j != nullptr) *jacobian_j = chain * between_j;
  return residual;
}

Eigen::Vector2d RangeBearingResidual(const Eigen::Vector3d& pose, const Eigen::Vector2d& point,
                                     const Eigen::Vector2d& measured_range_bearing,
                                     const SensorMount& mount,
                                     Eigen::Matrix<double, 2, 3>* jacobian_pose,
                                     Eigen::Matrix2d* jacobian_point) {
  const Eigen::Vector2d sensor = SensorPosition(pose, mount);
  if ((point - sensor).norm() <= kMinPredictedRange_m) {
    if (jacobian_pose != nullptr) jacobian_pose->setZero();
    if (jacobian_point != nullptr) jacobian_point->setZero();
    return Eigen::Vector2d((point - sensor).norm() - measured_range_bearing(0), 0.0);
  }
  const Eigen::Vector2d predicted =
      PredictRangeBearing(pose, point, mount, jacobian_pose, jacobian_point);
  return Eigen::Vector2d(predicted(0) - measured_range_bearing(0),
                         WrapAngle(predicted(1) - measured_range_bearing(1)));
}

Eigen::Vector2d RelativePositionResidual(const Eigen::Vector3d& pose,
                                         const Eigen::Vector2d& point,
                                         const Eigen::Vector2d& measured_position,
                                         Eigen::Matrix<double, 2, 3>* jacobian_pose,
                                         Eigen::Matrix2d* jacobian_point) {
  const double c = std::cos(pose(2));
  const double s = std::sin(pose(2));
  const double dx = point(0) - pose(0);
  const double dy = point(1) - pose(1);
  const Eigen::Vector2d local(c * dx + s * dy, -s * dx + c * dy);
  if (jacobian_pose != nullptr) {
    *jacobian_pose << -c, -s, local(1),  //
        s, -c, -local(0);
  }
  if (jacobian_point != nullptr) {
    *jacobian_point << c, s,  //
        -s, c;
  }
  return local - measured_position;
}

Eigen::Vector3d PosePriorResidual(const Eigen::Vector3d& pose, const Eigen::Vector3d& measured,
                                  Eigen::Matrix3d* jacobian) {
  Eigen::Matrix3d error_pose;
  const Eigen::Vector3d error = PoseBetween(measured, pose, nullptr, &error_pose);
  Eigen::Matrix3d log_error;
  const Eigen::Vector3d residual = PoseLogarithm(error, &log_error);
  if (jacobian != nullptr) *jacobian = log_error * error_pose;
  return residual;
}

Eigen::Vector2d PointPriorResidual(const Eigen::Vector2d& point, const Eigen::Vector2d& measured,
                                   Eigen::Matrix2d* jacobian) {
  if (jacobian != nullptr) jacobian->setIdentity();
  return point - measured;
}

template <int kDim>
std::optional<std::string> SquareRootInformation(
    const Eigen::Matrix<double, kDim, kDim>& information,
    Eigen::Matrix<double, kDim, kDim>* root) {
  if (!information.allFinite()) return "information matrix has a non-finite entry";
  const double scale = information.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return "information matrix is zero";
  if ((information - information.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    return "information matrix is not symmetric";
  }
  const Eigen::Matrix<double, kDim, kDim> symmetric =
      0.5 * (information + information.transpose());
  const Eigen::LLT<Eigen::Matrix<double, kDim, kDim>> llt(symmetric);
  const double largest_diagonal = symmetric.diagonal().maxCoeff();
  if (llt.info() != Eigen::Success ||
      !(llt.matrixL().toDenseMatrix().diagonal().array().square() >
        1e-12 * largest_diagonal)
           .all()) {
    return "information matrix is not positive definite";
  }
  *root = llt.matrixU();
  return std::nullopt;
}

template std::optional<std::string> SquareRootInformation<2>(const Eigen::Matrix2d&,
                                                             Eigen::Matrix2d*);
template std::optional<std::string> SquareRootInformation<3>(const Eigen::Matrix3d&,
                                                             Eigen::Matrix3d*);

}  // namespace slammtt
