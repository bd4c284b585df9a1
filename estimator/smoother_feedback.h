// The smoother's estimate fed back into the filter (issue 14, item 2: "feeding the smoothed map
// back into the estimator, correcting its static landmarks and pose after a solve";
// docs/smoother.md, "Feedback"). Pure: no LCM, no clock.
//
// What arrives: after a solve, the smoother's robot pose at one scan (SMOOTHED_POSE) and the
// positions of its landmarks (SMOOTHED_MAP, the estimator's ids), both with that scan's utime.
//
// How the filter takes it: the means move, the covariance stays. The confirmed static point
// landmarks that the smoother holds (in the state or in the local window's archive) move to
// the smoother's positions, and the robot's pose to the smoother's pose carried forward to the
// filter's newest scan (ScanPoseHistory). Nothing else changes: not the covariance, not the
// heading drift b, not the movers, tentative or undecided objects, lines, nor the books.
//
// Why the mean only, not a pseudo-measurement: the smoother's estimate is computed from the
// very odometry and sightings the filter has fused already (SMOOTHER_INPUT is the filter's own
// associations). Fusing it as a measurement with the smoother's marginal covariance would count
// every sighting twice, and again at every solve (once a second); the filter's covariance would
// shrink far below its error and its gates with it, which breaks the association the feedback
// is meant to help. The smoother's advantage is not more information but a better use of it:
// it relinearises every factor at the current estimate, where the EKF linearised each sighting
// once at the pose of its scan. So the filter keeps its own (consistent, if linearised)
// uncertainty and takes the smoother's mean as the better linearisation point of the same
// information: the same step an iterated filter takes, in the filter's gauge (both are
// anchored at the first pose, docs/smoother.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "estimator/landmark_window.h"
#include "estimator/slam_state.h"

namespace slammtt {

// What the smoother estimated at one scan.
struct SmoothedEstimate {
  int64_t utime = 0;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // the robot at utime (x, y, heading)
  std::vector<std::pair<int64_t, Eigen::Vector2d>> landmarks;  // estimator id, position (m)
};

// What one feedback did.
struct FeedbackCounts {
  bool applied = false;            // false: the scan is no longer in the pose history (stale)
  int landmarks_moved = 0;         // in the state
  int archived_moved = 0;          // in the local window's archive
  int landmarks_unknown = 0;       // not a confirmed static landmark of the filter any more
  double pose_shift_m = 0.0;       // the robot's position moved by
  double heading_shift_rad = 0.0;  // its heading turned by (wrapped)
  double largest_landmark_shift_m = 0.0;
};

// The filter's pose after each of its last scans (the newest last), so that an estimate of
// the smoother for an earlier scan (live, the smoother is a scan or so behind) can be carried
// forward along the filter's own motion since. After a correction only the corrected newest
// pose is kept: the older ones are in the frame before it.
class ScanPoseHistory {
 public:
  explicit ScanPoseHistory(int capacity = 64) : capacity_(capacity) {}
  void Record(int64_t utime, const Eigen::Vector3d& pose);
  std::optional<Eigen::Vector3d> At(int64_t utime) const;
  // Forget everything but the newest scan, whose pose becomes `pose`.
  void KeepNewestAs(const Eigen::Vector3d& pose);
  void Clear() { poses_.clear(); }
  bool empty() const { return poses_.empty(); }
  int64_t newest_utime() const { return poses_.back().first; }
  const Eigen::Vector3d& newest_pose() const { return poses_.back().second; }

 private:
  int capacity_;
  std::deque<std::pair<int64_t, Eigen::Vector3d>> poses_;
};

// The smoother's pose at an earlier scan carried forward to now along the filter's motion
// since: smoothed * (filter_then^-1 * filter_now) (SE(2)).
Eigen::Vector3d CarryPoseForward(const Eigen::Vector3d& smoothed_then,
                                 const Eigen::Vector3d& filter_then,
                                 const Eigen::Vector3d& filter_now);

// Moves the robot's pose to `pose_now` and every confirmed static point landmark (no velocity
// states, not a person: MayLeaveTheState) named in `smoothed` to its smoothed position, in
// the state and in `archive` (may be null). The covariance is not touched.
FeedbackCounts ShiftToSmoothedEstimate(const SmoothedEstimate& smoothed,
                                       const Eigen::Vector3d& pose_now, SlamState* state,
                                       LandmarkArchive* archive);

}  // namespace slammtt
