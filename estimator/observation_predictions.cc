#include "estimator/observation_predictions.h"

#include <algorithm>
#include <cmath>

#include "estimator/track_management.h"

namespace slammtt {

int HoldBackUnsureReentries(const SlamState& state, double max_range_m, const FieldOfView& view,
                            std::vector<ObjectPrediction>* predictions) {
  int held_back = 0;
  for (int k = 0; k < state.num_objects() && k < static_cast<int>(predictions->size()); ++k) {
    if (!state.object(k).record.reentered_unseen) continue;
    ObjectPrediction& p = (*predictions)[static_cast<size_t>(k)];
    if (!p.valid) continue;
    const double range_sigma_m = std::sqrt(std::max(p.hph(0, 0), 0.0));
    if (SurelyInGeometry(p.range_bearing, range_sigma_m, max_range_m, view)) continue;
    p.valid = false;
    p.held_back = true;
    ++held_back;
  }
  return held_back;
}

const std::vector<ObjectPrediction>& ObservationPredictions::At(const SlamState& state) {
  if (state_ != &state || revision_ != state.revision() || computations_ == 0) {
    predictions_ = PredictObservations(state, mount_);
    if (hold_back_) slammtt::HoldBackUnsureReentries(state, max_range_m_, view_, &predictions_);
    state_ = &state;
    revision_ = state.revision();
    ++computations_;
  }
  return predictions_;
}

}  // namespace slammtt
