// Constant-velocity model of a moving object in the map plane (paper section 2.2, eqs. 6-8).
//
// State of one object: (x, y, vx, vy) in the map frame. Acceleration is process noise: a
// piecewise-constant acceleration of standard deviation sigma_q [m/s^2] over each step, which
// gives the covariance of eq. 8.
//
// The filter (ekf_prediction.h: PredictMovers) runs this model on every object with velocity
// states through PredictConstantVelocityInPlace, which applies eqs. 6-7 to that object's slots of
// the whole state; the tests check it against T(dt) X and T(dt) P T(dt)^T
// (tests/estimator/models_test.cc).
#pragma once

#include <Eigen/Core>

namespace slammtt {

// Eq. 7: T(dt) = [I dt*I; 0 I].
Eigen::Matrix4d ConstantVelocityTransition(double dt_s);

// Eq. 8: Q_d = sigma_q^2 [dt^4/4 I, dt^3/2 I; dt^3/2 I, dt^2 I].
Eigen::Matrix4d ConstantVelocityProcessNoise(double dt_s, double sigma_q_mps2);

// Eq. 6 without the noise: X(k+1) = T(dt) X(k). The Jacobian is T itself (linear model).
Eigen::Vector4d PredictConstantVelocity(const Eigen::Vector4d& state, double dt_s,
                                        Eigen::Matrix4d* jacobian = nullptr);

// Eqs. 6-7 on one object of a larger state, in place: the object's position is at mean(p),
// mean(p + 1) and its velocity at mean(v), mean(v + 1) (the two slots need not be adjacent).
// x <- T x and P <- T P T^T, where T is the identity except T(dt) on (p, p + 1, v, v + 1): only
// the object's position rows and columns change (row p += dt row v, then column p += dt column
// v, and likewise for p + 1), O(n), no n x n product. The rows are computed before the columns,
// so the position rows and columns of P may differ in the last bit: mirror the rows onto the
// columns afterwards to keep P exactly symmetric (SlamState::MirrorRowToColumn).
void PredictConstantVelocityInPlace(double dt_s, int p, int v, Eigen::Ref<Eigen::VectorXd> mean,
                                    Eigen::Ref<Eigen::MatrixXd> covariance);

}  // namespace slammtt
