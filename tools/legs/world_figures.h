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

// Where the person features come from, by the first surfaces of their legs' beams (the world
// knows what each beam hit): the diagnosis behind the figures (`slammtt-legs world --causes`).
enum class LegSource {
  kPersonLeg,      // a real person's leg (the feature is then misplaced, or pairs two people)
  kWallEnd,        // a wall within 0.15 m of its end (door jamb, corner) or two walls
  kWallPiece,      // a wall, away from its ends
  kFurnitureSide,  // a side of a desk, box or cabinet
  kFurnitureLeg,   // a chair or table leg (thin static circle of kind furniture)
  kPost,           // a pillar or bin
  kMixedPixel,     // most beams are mixed pixels between two surfaces
};
constexpr int kLegSources = 7;
const char* LegSourceName(LegSource source);

struct PersonCauses {
  // False person features (neither matched nor ignored): one-leg ones by the source of their
  // leg, pairs by the sources of both legs ([lower][higher]).
  int64_t false_one_leg[kLegSources] = {};
  int64_t false_pairs[kLegSources][kLegSources] = {};
  // False one-leg people on a person's leg that no feature of the scan matched: the person's
  // only feature, placed too far from its centre (the distance from the feature to that centre,
  // and from the farther of the person's two legs to it: a walker's trailing leg).
  std::vector<double> false_one_leg_alone_to_centre_m;
  std::vector<double> false_one_leg_alone_farther_leg_m;
  // Matched person features: centre errors of one-leg and two-leg people; pairs whose two legs
  // come from two different people (or a person and something else).
  std::vector<double> one_leg_errors_m;
  std::vector<double> pair_errors_m;
  // Matched pairs: distance from the feature to the midpoint of the person's two legs, and from
  // that midpoint to the person's centre (the world's gait: a walking body leads its legs).
  std::vector<double> pair_errors_to_legs_m;
  std::vector<double> pair_body_to_legs_m;
  int64_t pairs_of_one_person = 0;
  int64_t pairs_mixed = 0;
  // One-leg people: the truth centre minus the feature, along the sight line (positive: the
  // person's centre lies beyond the leg) and across it, and whether the person's other leg was
  // hidden (fewer than 3 beams).
  std::vector<double> one_leg_radial_m;
  std::vector<double> one_leg_lateral_m;
  int64_t one_leg_other_hidden = 0;
  // Missed people (in the truth set, no feature within the match distance), by the best fate of
  // their legs' clusters (a cluster within 0.15 m of a leg): [0] a leg candidate (a person feature
  // formed elsewhere or paired wrongly), [1] a point feature below leg_threshold, [2] on a line,
  // [3] a structure piece, [4] a two-beam cluster not a leg, [5] no cluster.
  int64_t missed_by_fate[6] = {};
};

struct WorldFigures {
  PersonCauses causes;                // pooled over every seed
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
