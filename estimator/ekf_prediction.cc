#include "estimator/ekf_prediction.h"

#include <cmath>

#include "common/angle.h"
#include "estimator/constant_velocity_model.h"

namespace slammtt {

void ApplyRobotPrediction(const Eigen::Vector3d& new_pose, const Eigen::Matrix4d& jacobian,
                          const Eigen::Matrix4d& noise, SlamState* state) {
  constexpr int kR = SlamState::kRobotDim;
  Eigen::Matrix4d f = jacobian;
  if (state->first_estimate_jacobians() && state->has_predicted_pose()) {
    // First-estimate Jacobians: the motion's Jacobian with respect to the heading is
    // J (p_new - p_start) for any chain of increments (J the 90-degree rotation); with p_start
    // the pose predicted for the previous scan instead of its updated estimate, the product of
    // the scans' Jacobians keeps the absolute heading unobservable (Huang et al. 2008).
    const Eigen::Vector3d& start = state->predicted_pose();
    f(0, 2) = -(new_pose(1) - start(1));
    f(1, 2) = new_pose(0) - start(0);
  }
  state->set_predicted_pose(new_pose);
  auto cov = state->covariance();
  // Rows, then columns: (F P) F^T restricted to the robot's rows and columns.
  const Eigen::Matrix<double, kR, Eigen::Dynamic> rows = f * cov.topRows(kR);
  cov.topRows(kR) = rows;
  const Eigen::Matrix<double, Eigen::Dynamic, kR> cols = cov.leftCols(kR) * f.transpose();
  cov.leftCols(kR) = cols;
  const Eigen::Matrix4d robot = cov.topLeftCorner<kR, kR>() + noise;
  cov.topLeftCorner<kR, kR>() = 0.5 * (robot + robot.transpose());
  // Rows and columns were computed in different summation orders: make them bit-identical.
  for (int i = 0; i < kR; ++i) state->MirrorRowToColumn(i);
  state->mean().head<3>() = new_pose;
}

void ApplyRobotPrediction(const Eigen::Vector3d& new_pose, const Eigen::Matrix3d& jacobian,
                          const Eigen::Matrix3d& noise, SlamState* state) {
  Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
  f.topLeftCorner<3, 3>() = jacobian;
  Eigen::Matrix4d q = Eigen::Matrix4d::Zero();
  q.topLeftCorner<3, 3>() = noise;
  ApplyRobotPrediction(new_pose, f, q, state);
}

void PredictMovers(double dt_s, double sigma_q_moving_mps2, double sigma_q_moving_person_mps2,
                   double sigma_q_undecided_mps2, SlamState* state) {
  auto mean = state->mean();
  auto cov = state->covariance();
  const Eigen::Matrix4d q_moving = ConstantVelocityProcessNoise(dt_s, sigma_q_moving_mps2);
  const Eigen::Matrix4d q_moving_person =
      ConstantVelocityProcessNoise(dt_s, sigma_q_moving_person_mps2);
  const Eigen::Matrix4d q_undecided = ConstantVelocityProcessNoise(dt_s, sigma_q_undecided_mps2);
  for (const StateObject& o : state->objects()) {
    if (!o.has_velocity()) continue;
    const bool moving = o.record.object_class == ObjectClass::kMoving;
    const bool person = o.record.kind == ObjectKind::kPerson;
    const Eigen::Matrix4d& q = !moving ? q_undecided : person ? q_moving_person : q_moving;
    const int p = o.position_index;
    const int v = o.velocity_index;
    // Eqs. 6-7 on this object's rows and columns (constant_velocity_model.h).
    PredictConstantVelocityInPlace(dt_s, p, v, mean, cov);
    // Eq. 8 on the (p, v) blocks.
    cov.block<2, 2>(p, p) += q.topLeftCorner<2, 2>();
    cov.block<2, 2>(p, v) += q.topRightCorner<2, 2>();
    cov.block<2, 2>(v, p) += q.bottomLeftCorner<2, 2>();
    cov.block<2, 2>(v, v) += q.bottomRightCorner<2, 2>();
    state->MirrorRowToColumn(p);
    state->MirrorRowToColumn(p + 1);
  }
}

void InflateMoverVelocities(const Eigen::Matrix2d& added, SlamState* state) {
  auto cov = state->covariance();
  for (const StateObject& o : state->objects()) {
    if (!o.has_velocity()) continue;
    cov.block<2, 2>(o.velocity_index, o.velocity_index) += added;
  }
}

void AddVelocityJump(int k, double dt_s, double sigma_mps, SlamState* state) {
  const StateObject& o = state->object(k);
  if (!o.has_velocity()) return;
  const double q = sigma_mps * sigma_mps;
  auto cov = state->covariance();
  const int p = o.position_index;
  const int v = o.velocity_index;
  cov.block<2, 2>(p, p) += q * dt_s * dt_s * Eigen::Matrix2d::Identity();
  cov.block<2, 2>(p, v) += q * dt_s * Eigen::Matrix2d::Identity();
  cov.block<2, 2>(v, p) += q * dt_s * Eigen::Matrix2d::Identity();
  cov.block<2, 2>(v, v) += q * Eigen::Matrix2d::Identity();
}

RobotMotionAccumulator::RobotMotionAccumulator(const Eigen::Vector3d& start_pose,
                                               double heading_drift_rad_per_m,
                                               double heading_drift_walk_var_per_m)
    : pose_(start_pose),
      heading_drift_rad_per_m_(heading_drift_rad_per_m),
      heading_drift_walk_var_per_m_(heading_drift_walk_var_per_m) {}

void RobotMotionAccumulator::Add(const OdometryIncrement& increment,
                                 const Eigen::Matrix2d& increment_covariance) {
  Eigen::Matrix4d f;
  Eigen::Matrix<double, 4, 2> g;
  pose_ = PredictRobotPoseWithHeadingDrift(pose_, heading_drift_rad_per_m_, increment, &f, &g);
  jacobian_ = f * jacobian_;
  noise_ = f * noise_ * f.transpose() + g * increment_covariance * g.transpose();
  noise_(SlamState::kHeadingDriftIndex, SlamState::kHeadingDriftIndex) +=
      heading_drift_walk_var_per_m_ * std::abs(increment.distance_m);
}

void RobotMotionAccumulator::AddPoseNoise(const Eigen::Matrix3d& noise) {
  noise_.topLeftCorner<3, 3>() += noise;
}

void RobotMotionAccumulator::AddPoseIncrement(const Eigen::Vector3d& increment,
                                              const Eigen::Matrix3d& covariance) {
  const double c = std::cos(pose_.z());
  const double s = std::sin(pose_.z());
  // pose' = pose (+) increment; F = d pose' / d pose, G = d pose' / d increment.
  Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
  f(0, 2) = -s * increment.x() - c * increment.y();
  f(1, 2) = c * increment.x() - s * increment.y();
  Eigen::Matrix<double, 4, 3> g = Eigen::Matrix<double, 4, 3>::Zero();
  g.topLeftCorner<2, 2>() << c, -s, s, c;
  g(2, 2) = 1.0;
  pose_ += Eigen::Vector3d(c * increment.x() - s * increment.y(),
                           s * increment.x() + c * increment.y(), increment.z());
  pose_.z() = WrapAngle(pose_.z());
  jacobian_ = f * jacobian_;
  noise_ = f * noise_ * f.transpose() + g * covariance * g.transpose();
}

}  // namespace slammtt
