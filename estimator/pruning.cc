#include "estimator/pruning.h"

#include <algorithm>
#include <cmath>

#include "estimator/track_management.h"

namespace slammtt {

std::vector<int> ObjectsToPrune(int64_t utime, const EstimatorOptions& options,
                                const std::vector<ObjectPrediction>& after_updates,
                                const SlamState& state, const Assignment& assignment) {
  std::vector<int> prune;
  if (options.mode == AssociationMode::kStaticNearestNeighbour) return prune;
  const FieldOfView view = FieldOfViewOf(options);
  for (int j = 0; j < assignment.num_objects(); ++j) {
    const StateObject& object = state.object(j);
    const ObjectPrediction& p = after_updates[static_cast<size_t>(j)];
    const bool out_of_view = !p.valid || p.range_bearing(0) > options.max_range_m ||
                             view.Excludes(p.range_bearing(1));
    const Eigen::Matrix2d position_cov =
        state.covariance().block<2, 2>(object.position_index, object.position_index);
    const double position_sigma = std::sqrt(std::max(position_cov(0, 0), position_cov(1, 1)));
    if (ShouldPrune(object.record, object.has_velocity(), utime, out_of_view, position_sigma,
                    options.tracks)) {
      prune.push_back(j);
    }
  }
  return prune;
}

void PruneObjects(int64_t utime, const std::vector<int>& taken_over,
                  const EstimatorOptions& options,
                  const std::vector<ObjectPrediction>& after_updates,
                  const Assignment& assignment, SlamState* state, StepCounts* counts,
                  LandmarkArchive* archive) {
  std::vector<int> prune = ObjectsToPrune(utime, options, after_updates, *state, assignment);
  if (archive != nullptr && options.window.radius_m > 0.0) {
    const int kept = archive->Store(*state, prune);
    counts->landmarks_archived += kept;
    counts->pruned = static_cast<int>(prune.size()) - kept;
  } else {
    counts->pruned = static_cast<int>(prune.size());
  }
  for (int j : taken_over) {
    if (std::find(prune.begin(), prune.end(), j) == prune.end()) prune.push_back(j);
  }
  state->RemoveObjects(prune);
}

}  // namespace slammtt
