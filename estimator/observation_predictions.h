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

#include "estimator/gating.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

class ObservationPredictions {
 public:
  explicit ObservationPredictions(const SensorMount& mount) : mount_(mount) {}

  // The predictions of every object of `state` as it is now (index = object index). The
  // reference stays valid until the next At() with a changed or another state.
  const std::vector<ObjectPrediction>& At(const SlamState& state);

  // How many times the predictions were computed.
  int computations() const { return computations_; }

 private:
  SensorMount mount_;
  const SlamState* state_ = nullptr;
  uint64_t revision_ = 0;
  std::vector<ObjectPrediction> predictions_;
  int computations_ = 0;
};

}  // namespace slammtt
