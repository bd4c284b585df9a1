// Constant-velocity model of a moving object in the map plane (paper section 2.2, eqs. 6-8).
//
// State of one object: (x, y, vx, vy) in the map frame. Acceleration is process noise: a
// piecewise-constant acceleration of standard deviation sigma_q [m/s^2] over each step, which
// gives the covariance of eq. 8.
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

}  // namespace slammtt
