#include "estimator/smoother_input.h"

#include <cmath>

#include "common/angle.h"

namespace slammtt {

void MotionIncrement(const RobotMotion& motion, Eigen::Vector3d* increment,
                     Eigen::Matrix3d* covariance) {
  const double c = std::cos(motion.from_pose(2));
  const double s = std::sin(motion.from_pose(2));
  Eigen::Matrix3d to_start_frame = Eigen::Matrix3d::Identity();
  to_start_frame.topLeftCorner<2, 2>() << c, s, -s, c;  // R^T
  const Eigen::Vector3d difference = motion.to_pose - motion.from_pose;
  *increment = to_start_frame * difference;
  (*increment)(2) = WrapAngle(difference(2));
  const Eigen::Matrix3d rotated = to_start_frame * motion.noise * to_start_frame.transpose();
  *covariance = 0.5 * (rotated + rotated.transpose());
}

SmootherScanInput SmootherInputBuilder::Build(const ScanResult& result,
                                              const SensorMount& mount) {
  SmootherScanInput input;
  input.utime = result.utime;
  input.pose = result.pose;
  input.pose_covariance = result.pose_covariance;
  input.continues = result.motion.continues;
  if (input.continues) {
    MotionIncrement(result.motion, &input.increment, &input.increment_covariance);
  } else {
    reported_.clear();
  }
  input.mount = mount;
  input.observations = result.static_observations;

  // A landmark observed in this scan stays, whatever its reported confirmation says.
  std::set<int64_t> still_static;
  for (const StaticObservation& o : input.observations) still_static.insert(o.landmark_id);
  for (const ObjectEstimate& e : result.objects) {
    if (MayBePointLandmark(e.object_class, e.kind)) still_static.insert(e.id);
  }
  // The local window's archive (landmark_window.h) holds landmarks, not removals.
  for (const ObjectEstimate& e : result.archived_landmarks) still_static.insert(e.id);
  for (auto it = reported_.begin(); it != reported_.end();) {
    if (still_static.count(*it) == 0) {
      input.removed_landmark_ids.push_back(*it);
      it = reported_.erase(it);
    } else {
      ++it;
    }
  }
  for (const StaticObservation& o : input.observations) reported_.insert(o.landmark_id);
  return input;
}

}  // namespace slammtt
