#include "estimator/observation_predictions.h"

namespace slammtt {

const std::vector<ObjectPrediction>& ObservationPredictions::At(const SlamState& state) {
  if (state_ != &state || revision_ != state.revision() || computations_ == 0) {
    predictions_ = PredictObservations(state, mount_);
    state_ = &state;
    revision_ = state.revision();
    ++computations_;
  }
  return predictions_;
}

}  // namespace slammtt
