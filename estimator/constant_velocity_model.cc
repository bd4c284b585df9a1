#include "estimator/constant_velocity_model.h"

namespace slammtt {

Eigen::Matrix4d ConstantVelocityTransition(double dt_s) {
  Eigen::Matrix4d transition = Eigen::Matrix4d::Identity();
  transition(0, 2) = dt_s;
  transition(1, 3) = dt_s;
  return transition;
}

Eigen::Matrix4d ConstantVelocityProcessNoise(double dt_s, double sigma_q_mps2) {
  const double dt2 = dt_s * dt_s;
  const double q = sigma_q_mps2 * sigma_q_mps2;
  const double position = q * dt2 * dt2 / 4.0;
  const double cross = q * dt2 * dt_s / 2.0;
  const double velocity = q * dt2;
  Eigen::Matrix4d noise;
  noise << position, 0.0, cross, 0.0,  //
      0.0, position, 0.0, cross,       //
      cross, 0.0, velocity, 0.0,       //
      0.0, cross, 0.0, velocity;
  return noise;
}

Eigen::Vector4d PredictConstantVelocity(const Eigen::Vector4d& state, double dt_s,
                                        Eigen::Matrix4d* jacobian) {
  if (jacobian != nullptr) *jacobian = ConstantVelocityTransition(dt_s);
  Eigen::Vector4d next = state;
  next.head<2>() += dt_s * state.tail<2>();
  return next;
}

void PredictConstantVelocityInPlace(double dt_s, int p, int v, Eigen::Ref<Eigen::VectorXd> mean,
                                    Eigen::Ref<Eigen::MatrixXd> covariance) {
  mean.segment<2>(p) += dt_s * mean.segment<2>(v);
  covariance.row(p) += dt_s * covariance.row(v);
  covariance.row(p + 1) += dt_s * covariance.row(v + 1);
  covariance.col(p) += dt_s * covariance.col(v);
  covariance.col(p + 1) += dt_s * covariance.col(v + 1);
}

}  // namespace slammtt
