// The landmarks of a scenario's scattered_landmarks section (scenario.h, ScatteredLandmarksSpec)
// placed along the robot's waypoint path: the large-loop family of issue 14 (thousands of point
// landmarks over hundreds of metres, config/scenarios/large-loop.yaml) is written as a path and
// a count instead of a list.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tools/world/scenario.h"

namespace slammtt {

// `spec.count` circles (kind post, ids spec.first_id, ...) along `path` (the closed polygon
// through its points when `closed`, else the open polyline), drawn from `rng` by the rules of
// ScatteredLandmarksSpec. Returns fewer than spec.count when the spacing leaves no room: each
// landmark gets at most 1000 draws (the caller reports the shortfall). Empty for a count of 0
// or a path of fewer than two points.
std::vector<StaticObjectSpec> ScatterLandmarks(const ScatteredLandmarksSpec& spec,
                                               const std::vector<PlanarPoint>& path, bool closed,
                                               std::mt19937_64& rng);

// `scenario` with its scattered landmarks drawn from `seed` (a stream of their own) appended to
// its statics and the section cleared (count 0). std::invalid_argument naming the section when
// the spacing leaves room for fewer landmarks than asked.
Scenario WithScatteredLandmarks(const Scenario& scenario, uint64_t seed);

}  // namespace slammtt
