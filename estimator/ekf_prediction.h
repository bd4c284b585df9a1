// EKF prediction of the whole state to the next scan (paper eqs. 9, 18-19), exploiting its
// block structure: the transition of eq. 9 is block-diagonal (robot F, landmarks I, movers T),
// so only the robot's and the movers' rows and columns change, in O(n) per robot step and per
// mover; no dense n x n Jacobian is ever formed and landmark-landmark blocks are not touched.
#pragma once

#include <Eigen/Core>

#include "estimator/robot_motion_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Robot part of eq. 19 on the robot block (pose and heading drift, slam_state.h): P_rr <- F
// P_rr F^T + Q, P_rx <- F P_rx (and the mirror), pose <- new_pose; the drift's mean is left as
// it is (the step does not change it). `new_pose` is f(x) (eq. 18), `jacobian` is F (4x4 over
// x, y, heading, b), `noise` is G Q G^T plus the drift's random walk (4x4).
void ApplyRobotPrediction(const Eigen::Vector3d& new_pose, const Eigen::Matrix4d& jacobian,
                          const Eigen::Matrix4d& noise, SlamState* state);
// The same for a transition that ignores the drift: F = diag(jacobian, 1), Q = diag(noise, 0).
void ApplyRobotPrediction(const Eigen::Vector3d& new_pose, const Eigen::Matrix3d& jacobian,
                          const Eigen::Matrix3d& noise, SlamState* state);

// Mover part of eq. 9: every object with velocity states follows eq. 6 over dt_s with the
// process noise of eq. 8: sigma_q_moving_mps2 for objects classified MOVING (of kind PERSON:
// sigma_q_moving_person_mps2, people.h), sigma_q_undecided_mps2 for the others (not yet
// classified).
void PredictMovers(double dt_s, double sigma_q_moving_mps2, double sigma_q_moving_person_mps2,
                   double sigma_q_undecided_mps2, SlamState* state);

// Adds `added` (2x2, symmetric PSD) to the velocity covariance of every object with velocity
// states: used when the time since the last scan is too long to trust the constant-velocity
// model (the estimator's time-gap handling).
void InflateMoverVelocities(const Eigen::Matrix2d& added, SlamState* state);

// A velocity jump of covariance sigma^2 I at the start of the last dt_s for object k (which has
// velocity states): adds sigma^2 [dt^2 I, dt I; dt I, I] to its (position, velocity) block. The
// covariance resetting of manoeuvring targets (Bar-Shalom, Li and Kirubarajan, Estimation with
// Applications to Tracking and Navigation, 2001, section 11.2): used when a mover's measurement
// falls outside its gate right after a turn.
void AddVelocityJump(int k, double dt_s, double sigma_mps, SlamState* state);

// A chain of eq.-1 steps, each corrected by the heading drift b (PredictRobotPoseWithHeadingDrift),
// composed into one transition of the robot block (x, y, heading, b): the composed pose,
// Jacobian F = F_k ... F_1 (4x4) and noise Q = sum of the step noises propagated through the
// later steps. Applying it once costs the same O(n) as one step, whatever the number of
// odometry messages between two scans.
//
// b follows a random walk whose variance grows by `heading_drift_walk_var_per_m` per metre
// travelled (the wheels' effective sizes change slowly with load, tyre pressure and wear), so
// the filter keeps following it instead of becoming certain of an old value.
class RobotMotionAccumulator {
 public:
  explicit RobotMotionAccumulator(const Eigen::Vector3d& start_pose,
                                  double heading_drift_rad_per_m = 0.0,
                                  double heading_drift_walk_var_per_m = 0.0);
  // One eq.-1 step with the covariance (2x2 over distance, rotation) of its increment.
  void Add(const OdometryIncrement& increment, const Eigen::Matrix2d& increment_covariance);
  // Adds pose noise directly (3x3), e.g. for unmodelled motion.
  void AddPoseNoise(const Eigen::Matrix3d& noise);
  // One step by a pose increment (dx_m, dy_m, dheading_rad) in the robot frame, with its
  // covariance (3x3), from a motion source that is not the wheels (scan_alignment.h): the pose
  // composed with it; the heading drift b corrects wheel odometry only, so it is left out.
  void AddPoseIncrement(const Eigen::Vector3d& increment, const Eigen::Matrix3d& covariance);
  const Eigen::Vector3d& pose() const { return pose_; }
  const Eigen::Matrix4d& jacobian() const { return jacobian_; }
  const Eigen::Matrix4d& noise() const { return noise_; }

 private:
  Eigen::Vector3d pose_;
  double heading_drift_rad_per_m_;
  double heading_drift_walk_var_per_m_;
  Eigen::Matrix4d jacobian_ = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d noise_ = Eigen::Matrix4d::Zero();
};

}  // namespace slammtt
