// Differential-drive motion of the robot (paper section 2.1, eq. 1) and the noise of the
// odometry increments that drive it.
//
// Eq. 1 advances the pose (x, y, phi) by a travelled distance d = Omega^r * dt and a heading
// change delta = Omega^d * dt, the distance being travelled along the *new* heading:
//   x' = x + d cos(phi + delta),  y' = y + d sin(phi + delta),  phi' = phi + delta.
// The estimator feeds it increments measured by the base: the difference of two integrated
// odometry poses (odometry_t), or velocity times time when no odometry arrived.
#pragma once

#include <Eigen/Core>

#include "common/options_schema.h"

namespace slammtt {

// One step of eq. 1: the distance travelled by the axle centre (signed, negative when
// reversing) and the heading change (CCW positive).
struct OdometryIncrement {
  double distance_m = 0.0;
  double rotation_rad = 0.0;
};

// Eq. 1. Optionally returns the Jacobians with respect to the pose (F, 3x3) and to the
// increment (G, 3x2) for the EKF prediction (eq. 19: P' = F P F^T + G Q G^T).
Eigen::Vector3d PredictRobotPose(const Eigen::Vector3d& pose, const OdometryIncrement& increment,
                                 Eigen::Matrix3d* jacobian_pose = nullptr,
                                 Eigen::Matrix<double, 3, 2>* jacobian_increment = nullptr);

// Eq. 1 with the odometry's systematic heading drift b [rad per metre travelled] corrected:
// the true heading change is the measured one plus b * d (d signed: a wheel larger than its
// nominal size turns the robot by the same angle per metre it rolls, the other way when
// reversing: the type-B error of Borenstein and Feng, "Measurement and correction of systematic
// odometry errors in mobile robots", IEEE Trans. Robotics and Automation 12(6), 1996 (UMBmark):
// unequal wheel diameters give a heading error proportional to the distance travelled). So
// eq. 1 runs with the increment (d, delta + b d). b is a state of the EKF (slam_state.h); the
// step leaves it unchanged. Returns the new pose and optionally the
// Jacobians with respect to (x, y, heading, b) (4x4, last row (0 0 0 1)) and to the increment
// (4x2, last row zero).
Eigen::Vector3d PredictRobotPoseWithHeadingDrift(
    const Eigen::Vector3d& pose, double heading_drift_rad_per_m,
    const OdometryIncrement& increment, Eigen::Matrix4d* jacobian_robot = nullptr,
    Eigen::Matrix<double, 4, 2>* jacobian_increment = nullptr);

// The increment of eq. 1 that takes the odometry pose `from` to `to` (both in the base's own
// odometry frame): rotation = wrapped heading difference, distance = length of the
// displacement, negative when the displacement points backwards with respect to the heading at
// `to` (eq. 1 moves along the new heading). Exact inverse of PredictRobotPose for poses that
// eq. 1 produced; for other integration schemes the distance is still exact and the direction
// differs by at most half the rotation of the step.
OdometryIncrement IncrementBetweenOdometryPoses(const Eigen::Vector3d& from,
                                                const Eigen::Vector3d& to);

// Noise of one odometry increment, as variances that grow with the motion (independent
// encoder errors accumulate linearly in variance with the distance rolled, as in the usual
// odometry error models, e.g. Thrun, Burgard and Fox, Probabilistic Robotics, section 5.4).
// Defaults: a P3-DX with healthy wheels, as the synthetic base models it (0.5 % wheel slip per
// reading, 0.002 rad encoder noise, up to 0.05 % wheel-size bias; docs/world.md): about 1 cm
// per sqrt(m) along the path and 0.01 rad per sqrt(m) of heading, several times what the slip
// alone gives so that the wheel-size bias stays inside the model.
struct OdometryNoiseOptions {
  double distance_var_per_m = 1e-4;            // [m^2 per m travelled] (1 cm after 1 m)
  double rotation_var_per_rad = 1e-4;          // [rad^2 per rad turned]
  double rotation_var_per_m = 1e-4;            // [rad^2 per m travelled] (0.01 rad after 1 m)
  double distance_var_per_s = 1e-6;            // floor that keeps a standing robot well-posed
  double rotation_var_per_s = 1e-6;
};

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `odometry_noise`).
void VisitOdometryNoiseOptions(OptionVisitor* visitor, OdometryNoiseOptions* options);

// Covariance (2x2, diagonal) over (distance_m, rotation_rad) of an increment spanning dt_s.
Eigen::Matrix2d OdometryIncrementCovariance(const OdometryIncrement& increment, double dt_s,
                                            const OdometryNoiseOptions& noise);

}  // namespace slammtt
