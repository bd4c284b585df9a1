// The filter's local window of static landmarks (issue 14, item 3: no object cap that silently
// loses the map). The EKF's cost grows with the square of its state, and a map of thousands of
// landmarks along a long route does not fit in it; instead of refusing new objects at
// max_objects and forgetting what the map held, the state keeps the confirmed static landmarks
// near the robot and the archive keeps the others, each with its id, its mean and its marginal
// covariance as it left the state. The smoother (docs/smoother.md) keeps every landmark with its
// sightings, so when the robot comes back and a landmark re-enters the state under its own id,
// the smoother sees the same landmark again and closes the loop.
//
// Per scan, two steps of the estimator (estimator.h):
//   re-entry (after the prediction, before gating): every archived landmark whose mean lies
//     within reenter_radius_m of the robot's predicted position re-enters the state, nearest
//     first, while the state holds fewer than max_landmarks confirmed static landmarks (0: no
//     limit). It comes back with its archived mean and marginal covariance and no correlation
//     with anything else (SlamState::AddObject with a zero robot Jacobian): the correlations it
//     had when it left are gone, so the filter treats the landmark as an independent prior
//     (what an EKF with submaps does when it joins a stored map: Guivant and Nebot, IEEE T-RA
//     17(3), 2001, compressed filter). Its record comes back as it was (id, class, hits, first
//     and last sighting), with the evidence that describes the last scans (misses in view, the
//     offsets of the classifier) cleared;
//   leaving (at the end of the scan, after new objects): every confirmed STATIC point landmark
//     (no velocity states, not a person) whose mean lies farther than radius_m from the robot
//     leaves the state for the archive; then, while more than max_landmarks remain, the
//     farthest leave too. Undecided, moving and tentative objects never leave: the tracker
//     keeps and prunes them as before. A confirmed static landmark that pruning would drop for
//     being unseen in view goes to the archive too (pruning.h): with a window it is a part of
//     the map, not a track.
// reenter_radius_m <= radius_m gives the hysteresis that keeps a landmark at the edge from
// leaving and coming back every scan, and reenter_radius_m >= max_range_m (checked with the
// options) keeps every landmark the laser can see in the state, so that a sighting of an
// archived landmark never starts a duplicate. Off (radius_m 0, the default) neither step does
// anything and the estimator computes exactly what it computed without them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "common/options_schema.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct LandmarkWindowOptions {
  double radius_m = 0.0;          // 0: no window (every landmark stays in the state)
  double reenter_radius_m = 0.0;  // in [max_range_m, radius_m] when radius_m > 0
  int max_landmarks = 0;          // confirmed static landmarks in the state at most; 0: no limit
};

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `window`).
void VisitLandmarkWindowOptions(OptionVisitor* visitor, LandmarkWindowOptions* options);

// Empty when the window's options fit together and with the laser's max_range_m, else one line
// naming the key.
std::string CheckLandmarkWindowOptions(const LandmarkWindowOptions& options, double max_range_m);

// A landmark out of the state: its estimate as it left (map frame) and its book-keeping.
struct ArchivedLandmark {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();  // marginal, as it left
  ObjectRecord record;
};

// Whether object k of `state` may leave for the archive: a confirmed STATIC landmark without
// velocity states, not a person.
bool MayLeaveTheState(const SlamState& state, int k);

class LandmarkArchive {
 public:
  // Re-entry (above). Returns how many landmarks re-entered. Nothing without a window.
  int Restore(const LandmarkWindowOptions& options, SlamState* state);

  // Leaving (above). Returns how many landmarks left. Nothing without a window.
  int Archive(const LandmarkWindowOptions& options, SlamState* state);

  // Copies the objects of `state` listed in `indices` that may leave it (MayLeaveTheState)
  // into the archive, without removing them from the state (the caller does: pruning.h).
  // Returns how many.
  int Store(const SlamState& state, const std::vector<int>& indices);

  // By id.
  const std::map<int64_t, ArchivedLandmark>& landmarks() const { return landmarks_; }
  // Moves an archived landmark's mean (the smoother's feedback, smoother_feedback.h); false
  // when the id is not in the archive.
  bool MoveLandmark(int64_t id, const Eigen::Vector2d& position_m);
  int size() const { return static_cast<int>(landmarks_.size()); }
  void Clear() { landmarks_.clear(); }

 private:
  std::map<int64_t, ArchivedLandmark> landmarks_;
};

}  // namespace slammtt
