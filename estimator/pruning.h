// Track management, pruning (paper Algorithm 2, line 11; section 5.1's 3.5 s): the objects held
// before the scan's new objects that ShouldPrune (track_management.h) says to drop, judged at
// the state after the updates: out of view when the prediction lies outside the sensor's field
// of view or range (not merely too far for the segmenter to see a person), position sigma the
// larger standard deviation of the position estimate. Baseline (a), the static world, prunes
// nothing.
#pragma once

#include <vector>

#include "estimator/association.h"
#include "estimator/landmark_window.h"

namespace slammtt {

// Indices of the objects to prune, increasing. `after_updates`: the predictions at the state
// after the updates (before classification).
std::vector<int> ObjectsToPrune(int64_t utime, const EstimatorOptions& options,
                                const std::vector<ObjectPrediction>& after_updates,
                                const SlamState& state, const Assignment& assignment);

// Removes the objects to prune (counts->pruned) and the lost tracks whose identity went to a
// new object (reacquisition.h: `taken_over`). With a local window (options.window, `archive`
// not null) a confirmed static landmark among the objects to prune is part of the map, not a
// track: it leaves the state for the archive instead (counts->landmarks_archived), so that the
// map and the smoother keep it (landmark_window.h).
void PruneObjects(int64_t utime, const std::vector<int>& taken_over,
                  const EstimatorOptions& options,
                  const std::vector<ObjectPrediction>& after_updates,
                  const Assignment& assignment, SlamState* state, StepCounts* counts,
                  LandmarkArchive* archive = nullptr);

}  // namespace slammtt
