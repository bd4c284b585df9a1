#include "estimator/smoother_feedback.h"

#include <algorithm>
#include <unordered_map>

#include "common/angle.h"
#include "geometry/pose2.h"

namespace slammtt {

void ScanPoseHistory::Record(int64_t utime, const Eigen::Vector3d& pose) {
  poses_.emplace_back(utime, pose);
  while (static_cast<int>(poses_.size()) > capacity_) poses_.pop_front();
}

std::optional<Eigen::Vector3d> ScanPoseHistory::At(int64_t utime) const {
  for (auto it = poses_.rbegin(); it != poses_.rend(); ++it) {
    if (it->first == utime) return it->second;
    if (it->first < utime) break;
  }
  return std::nullopt;
}

void ScanPoseHistory::KeepNewestAs(const Eigen::Vector3d& pose) {
  if (poses_.empty()) return;
  const int64_t utime = poses_.back().first;
  poses_.clear();
  poses_.emplace_back(utime, pose);
}

Eigen::Vector3d CarryPoseForward(const Eigen::Vector3d& smoothed_then,
                                 const Eigen::Vector3d& filter_then,
                                 const Eigen::Vector3d& filter_now) {
  return ComposePoses(smoothed_then, PoseBetween(filter_then, filter_now));
}

FeedbackCounts ShiftToSmoothedEstimate(const SmoothedEstimate& smoothed,
                                       const Eigen::Vector3d& pose_now, SlamState* state,
                                       LandmarkArchive* archive) {
  FeedbackCounts counts;
  counts.applied = true;
  std::unordered_map<int64_t, int> index_of;  // id -> object index, movable landmarks only
  for (int k = 0; k < state->num_objects(); ++k) {
    if (MayLeaveTheState(*state, k)) index_of[state->object(k).record.id] = k;
  }
  auto mean = state->mean();
  const Eigen::Vector3d before = mean.head<3>();
  counts.pose_shift_m = (pose_now.head<2>() - before.head<2>()).norm();
  counts.heading_shift_rad = WrapAngle(pose_now(2) - before(2));
  mean.head<2>() = pose_now.head<2>();
  mean(2) = WrapAngle(pose_now(2));
  // The smoother's estimate is a new linearisation point (first-estimate Jacobians).
  state->set_predicted_pose(mean.head<3>());
  for (const auto& [id, position] : smoothed.landmarks) {
    const auto it = index_of.find(id);
    if (it != index_of.end()) {
      const int p = state->object(it->second).position_index;
      counts.largest_landmark_shift_m =
          std::max(counts.largest_landmark_shift_m, (position - mean.segment<2>(p)).norm());
      mean.segment<2>(p) = position;
      state->object(it->second).first_estimate_m = position;
      ++counts.landmarks_moved;
    } else if (archive != nullptr && archive->MoveLandmark(id, position)) {
      ++counts.archived_moved;
    } else {
      ++counts.landmarks_unknown;
    }
  }
  return counts;
}

}  // namespace slammtt
