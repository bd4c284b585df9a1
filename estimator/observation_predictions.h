// Step 2 of Algorithm 2 (paper eqs. 10-11 and 20-21): the predicted observation of every object
// (range, bearing, their Jacobians and H P H^T; gating.h: PredictObservations), computed once
// per state.
//
// Every step of a scan judges pairs at the state as it is when the step runs: gating at the
// predicted state, RANSAC after level 1's update, level 3 after level 2's and the manoeuvres'
// changes, track management after every update. Each state is predicted once, however many
// steps look at it: At() recomputes only when the state has changed since the previous call
// (SlamState::revision()), so a scan in which level 1 updates and nothing else changes the state
// predicts twice (the predicted state, the state after level 1) where every step used to
// predict again (up to nine times). The values are those PredictObservations gives for that
// state, bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include "estimator/field_of_view.h"
#include "estimator/gating.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Association after re-entry (the local window, landmark_window.h). A landmark comes back from
// the archive within window_reenter_radius_m >= max_range_m, so it may re-enter while its true
// position lies just beyond the laser's range; in a field of posts 1-2 m apart the measurement
// of an unmapped neighbour inside the range then falls in its gate alone, and one wrong update
// of a landmark the filter holds as an independent prior moves the robot (large-loop seed 1 at
// 323.6 s: the measurement of a post 1.9 m from the re-entered landmark and 1.1 m nearer, at
// 30.0 m, moved the pose by 0.5 m; the map followed). So until its first measurement after
// re-entry (ObjectRecord::reentered_unseen), a re-entered landmark is judged only where it is
// surely inside the laser's range and view (track_management.h: SurelyInGeometry, with the
// standard deviation of its predicted range, sqrt((H P H^T)_rr)): elsewhere its prediction is
// marked invalid, which every step reads as "not judged in this scan" (no pair at any level, no
// miss, no unseen time). Returns how many were marked.
int HoldBackUnsureReentries(const SlamState& state, double max_range_m, const FieldOfView& view,
                            std::vector<ObjectPrediction>* predictions);

class ObservationPredictions {
 public:
  explicit ObservationPredictions(const SensorMount& mount) : mount_(mount) {}
  // With the window on: every At() applies HoldBackUnsureReentries with this geometry.
  void HoldBackReentriesBeyond(double max_range_m, const FieldOfView& view) {
    hold_back_ = true;
    max_range_m_ = max_range_m;
    view_ = view;
  }

  // The predictions of every object of `state` as it is now (index = object index). The
  // reference stays valid until the next At() with a changed or another state.
  const std::vector<ObjectPrediction>& At(const SlamState& state);

  // How many times the predictions were computed.
  int computations() const { return computations_; }

 private:
  SensorMount mount_;
  bool hold_back_ = false;
  double max_range_m_ = 0.0;
  FieldOfView view_;
  const SlamState* state_ = nullptr;
  uint64_t revision_ = 0;
  std::vector<ObjectPrediction> predictions_;
  int computations_ = 0;
};

}  // namespace slammtt
