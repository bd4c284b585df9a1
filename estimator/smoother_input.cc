#include "estimator/smoother_input.h"

#include "geometry/pose2.h"

namespace slammtt {

void MotionIncrement(const RobotMotion& motion, Eigen::Vector3d* increment,
                     Eigen::Matrix3d* covariance) {
  // The end pose seen from the start pose; its Jacobian with respect to the end pose is
  // diag(R^T, 1), which carries the noise the prediction added to the end pose into that frame.
  Eigen::Matrix3d to_start_frame;
  *increment = PoseBetween(motion.from_pose, motion.to_pose, nullptr, &to_start_frame);
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
