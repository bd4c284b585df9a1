#include "estimator/scan_prediction.h"

#include <algorithm>
#include <cmath>

#include "estimator/ekf_prediction.h"

namespace slammtt {
namespace {

// The robot's motion over the interval: from the odometry, or standing still with the
// extrapolation noise when no odometry has ever arrived. Returns whether readings covered it.
bool AddRobotMotion(int64_t utime, const ScanInterval& interval, const EstimatorOptions& options,
                    OdometryBuffer* odometry, const ScanAlignment* aligned,
                    RobotMotionAccumulator* motion) {
  ExtrapolationNoise extrapolation;
  extrapolation.speed_var_per_s2 =
      options.extrapolation_speed_sigma_mps * options.extrapolation_speed_sigma_mps;
  extrapolation.turn_var_per_s2 =
      options.extrapolation_turn_sigma_radps * options.extrapolation_turn_sigma_radps;
  extrapolation.max_s = options.max_prediction_s;
  if (odometry->anchored()) {
    return odometry->AddMotionTo(utime, options.odometry_noise, extrapolation, motion);
  }
  if (aligned != nullptr && !interval.first_scan) {
    motion->AddPoseIncrement(aligned->increment, aligned->covariance);
    return false;
  }
  if (!interval.first_scan) {
    const double dt = interval.dt_s;
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    covariance(0, 0) = extrapolation.speed_var_per_s2 * dt * dt;
    covariance(1, 1) = extrapolation.turn_var_per_s2 * dt * dt;
    motion->Add(OdometryIncrement{}, covariance);
  }
  return false;
}

// A gap too long to trust the prediction: the robot's pose and the movers' velocities get
// uncertainty in proportion to the predicted interval.
void InflateForTimeGap(double dt, const EstimatorOptions& options, RobotMotionAccumulator* motion,
                       SlamState* state) {
  const double position_sigma = options.gap_robot_position_sigma_mps * dt;
  // A heading known to within more than half a turn is not known at all.
  const double heading_sigma = std::min(options.gap_robot_heading_sigma_radps * dt, M_PI);
  motion->AddPoseNoise(Eigen::Vector3d(position_sigma * position_sigma,
                                       position_sigma * position_sigma,
                                       heading_sigma * heading_sigma)
                           .asDiagonal());
  const double velocity_sigma = options.gap_mover_velocity_sigma_mps;
  InflateMoverVelocities(velocity_sigma * velocity_sigma * Eigen::Matrix2d::Identity(), state);
}

}  // namespace

PredictionNotes PredictToScan(int64_t utime, const ScanInterval& interval,
                              const EstimatorOptions& options, OdometryBuffer* odometry,
                              SlamState* state, const ScanAlignment* aligned) {
  // With the drift state off its variance stays exactly 0 (no random walk), so b stays 0.
  const double drift_walk_var_per_m =
      options.heading_drift_sigma_rad_per_m > 0.0 ? options.heading_drift_walk_var_per_m : 0.0;
  RobotMotionAccumulator motion(state->robot_pose(), state->heading_drift_rad_per_m(),
                                drift_walk_var_per_m);
  PredictionNotes notes;
  const bool covered = AddRobotMotion(utime, interval, options, odometry, aligned, &motion);
  notes.without_odometry = !interval.first_scan && !covered;
  notes.time_gap = interval.gap_s > options.max_time_gap_s;
  if (notes.time_gap) InflateForTimeGap(interval.dt_s, options, &motion, state);
  notes.motion.continues = !interval.first_scan;
  notes.motion.from_pose = state->robot_pose();
  notes.motion.to_pose = motion.pose();
  notes.motion.noise = motion.noise().topLeftCorner<3, 3>();
  ApplyRobotPrediction(motion.pose(), motion.jacobian(), motion.noise(), state);
  if (interval.dt_s > 0.0) {
    PredictMovers(interval.dt_s, options.mover_acceleration_sigma_mps2,
                  options.people.acceleration_sigma_mps2,
                  options.undecided_acceleration_sigma_mps2, state);
  }
  return notes;
}

}  // namespace slammtt
