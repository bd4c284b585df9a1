// What the smoother (docs/smoother.md) takes from one scan of the estimator, as plain data: the
// robot's motion since the previous scan as the EKF's motion model gave it, the measurements
// associated with static point landmarks, and the landmarks that left the static map. The
// estimator's stage publishes it as smoother_input_t (SMOOTHER_INPUT); slammtt-smoother reads it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <set>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/range_bearing_model.h"
#include "estimator/scan_prediction.h"
#include "estimator/static_observations.h"

namespace slammtt {

struct SmootherScanInput {
  int64_t utime = 0;
  // The filter's pose after the scan (map frame) and its covariance.
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  // False at the first scan of a time base: no motion from a previous scan.
  bool continues = false;
  // The motion from the previous scan, in the robot frame at the previous scan (x forward,
  // y left; dtheta wrapped), and its covariance over (dx, dy, dtheta). Zero when !continues.
  Eigen::Vector3d increment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d increment_covariance = Eigen::Matrix3d::Zero();
  SensorMount mount;
  std::vector<StaticObservation> observations;
  // Objects in `observations` of an earlier scan of this time base that can no longer be
  // landmarks: turned moving, pruned, removed by a state recovery, became a person; ascending.
  std::vector<int64_t> removed_landmark_ids;
};

// The motion's increment in the frame of its start pose, (R^T (t_to - t_from), wrap(dtheta)):
// PoseBetween(from, to) of geometry/pose2.h, the smoother's own; and the covariance of the
// prediction's noise in that frame, A Q A^T with A = diag(R^T, 1) (R the start heading's
// rotation): the noise the filter added to the end pose given the start.
void MotionIncrement(const RobotMotion& motion, Eigen::Vector3d* increment,
                     Eigen::Matrix3d* covariance);

// Builds one SmootherScanInput per processed scan. Keeps the ids of the landmarks it has
// reported observations of, to report their removal once; a scan that does not continue (a new
// time base) forgets them.
class SmootherInputBuilder {
 public:
  // `result` must be a processed scan (result.processed); `mount` is the estimator's.
  SmootherScanInput Build(const ScanResult& result, const SensorMount& mount);

 private:
  std::set<int64_t> reported_;  // landmark ids with observations in an earlier input
};

}  // namespace slammtt
