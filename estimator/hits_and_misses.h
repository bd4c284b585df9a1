// Track management, first step (paper Algorithm 2, line 11's book-keeping): every object held
// before the scan's new objects gets a hit or a miss (track_management.h).
//
// An object that got a measurement this scan is hit (RecordHit: confirmation by M of N,
// last_seen_m = its position after the updates; its kind from the measurement, people.h). One
// that got none is missed (RecordMiss) for the time since the previous scan, as "in geometry"
// when its prediction at the state after the updates lies surely inside the field of view and
// range, and as "expected visible" when it is also not in the shadow of any of the scan's
// features (ExpectedVisible; up to detection_range_m, 0: max_range_m). Baseline (a), the static
// world, counts no misses.
#pragma once

#include <cstdint>
#include <vector>

#include "estimator/association.h"

namespace slammtt {

// `after_updates`: the predictions at the current state; `widths_m`: of each measurement;
// `gap_s`: the time since the previous scan.
void RecordHitsAndMisses(const ScanAssociation& scan, const std::vector<double>& widths_m,
                         double gap_s, const EstimatorOptions& options,
                         const std::vector<ObjectPrediction>& after_updates,
                         const Assignment& assignment, SlamState* state);

}  // namespace slammtt
