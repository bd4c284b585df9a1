// The perception figures of issue 11 (Measure) on the synthetic world's scenarios (`office`,
// `office-hokuyo`, `corridor`): every scan the world publishes goes through the segmenter and
// is scored against the world's truth by tools/metrics/feature_score.h (people whose most
// visible leg has at least 3 beams, matched one-to-one within 0.3 m; point features on walls;
// lines against the true walls and furniture sides). Used by `slammtt-legs world` and the
// world figures test (tests/legs/world_figures_test.cc); docs/perception.md has the figures.
#pragma once

#include <cstdint>
#include <vector>

#include "perception/segmenter_options.h"
#include "tools/metrics/feature_score.h"
#include "tools/world/scenario.h"

namespace slammtt {

struct WorldFigures {
  FeatureScore pooled;                // over every seed
  std::vector<double> seed_recall;    // per seed, in seed order (NaN: no person in the truth set)
  std::vector<double> seed_precision;
  int64_t scans = 0;
};

// Runs `scenario` with each seed of `seeds` (the world's own randomness), keeps every
// `every`-th laser scan (every >= 1; std::invalid_argument otherwise, or for a scenario
// without laser scans), segments it with `options` as the message the world publishes
// (ToLaserScanMessage) and scores it with `score` (its max_range_m: "within 4 m").
WorldFigures MeasureWorldFigures(const Scenario& scenario, const std::vector<uint64_t>& seeds,
                                 const SegmenterOptions& options, int every,
                                 const FeatureScoreOptions& score);

}  // namespace slammtt
