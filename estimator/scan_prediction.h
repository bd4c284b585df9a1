// Step 1 of Algorithm 2 (line 2): the whole state predicted to the time of a scan (paper
// eqs. 9, 18-19; block-wise, ekf_prediction.h).
//
//  - The robot follows eq. 1 along the odometry received since the previous scan
//    (odometry_buffer.h), corrected by the heading drift state, all steps composed into one
//    transition. With no odometry ever received it moves by the alignment of the scan with the
//    previous one when the estimator gives one (scan_alignment.h), else it stands still, with
//    the extrapolation noise over the interval; the map frame is the robot's pose at the first
//    message, so at the first scan the motion since the first odometry reading counts too.
//  - After a time gap (the interval exceeds max_time_gap_s) the robot's pose gets
//    gap_robot_position_sigma_mps and gap_robot_heading_sigma_radps (at most pi) per second of
//    the predicted interval, and every mover's velocity gap_mover_velocity_sigma_mps, instead of
//    trusting a long prediction.
//  - Objects with velocity states follow eq. 6 with eq. 8's noise (moving and undecided ones
//    with their own acceleration sigma); landmarks are unchanged.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "estimator/estimator_options.h"
#include "estimator/odometry_buffer.h"
#include "estimator/scan_alignment.h"
#include "estimator/slam_state.h"

namespace slammtt {

// The time from the previous scan to this one.
struct ScanInterval {
  bool first_scan = true;
  double gap_s = 0.0;  // since the previous scan (0 at the first)
  double dt_s = 0.0;   // the part of it predicted: at most max_prediction_s
};

// The robot's part of one prediction, for the smoother (smoother_input.h): the pose before
// and after it (map frame) and the pose noise it added, G Q G^T with the time-gap inflation
// (3x3 over x, y, heading of the map frame; the heading drift's random walk left out).
struct RobotMotion {
  bool continues = false;  // false at the first scan: no previous scan to move from
  Eigen::Vector3d from_pose = Eigen::Vector3d::Zero();
  Eigen::Vector3d to_pose = Eigen::Vector3d::Zero();
  Eigen::Matrix3d noise = Eigen::Matrix3d::Zero();
};

// What the prediction had to make up for, for the estimator's counters and events, and the
// robot's motion it applied.
struct PredictionNotes {
  bool without_odometry = false;  // not the first scan, and no reading covered the interval
  bool time_gap = false;          // gap_s > max_time_gap_s: uncertainty inflated
  RobotMotion motion;
};

// `aligned` (optional): the robot's motion since the previous scan from the static structure
// (scan_alignment.h), used instead of standing still when no odometry has ever arrived.
PredictionNotes PredictToScan(int64_t utime, const ScanInterval& interval,
                              const EstimatorOptions& options, OdometryBuffer* odometry,
                              SlamState* state, const ScanAlignment* aligned = nullptr);

}  // namespace slammtt
