// The perception figures of issue 11 (Measure) on the world's legged-people scenarios
// (tools/legs/world_figures.h): `office` and `corridor` (RPLIDAR A2, 0.9 degrees, scored within
// 4 m) and `office-hokuyo` (0.35 degrees, every range), seeds 1-20, every 10th scan. No seed
// here is a training seed of the leg classifier (101-106, scripts/train-leg-model.sh). Floors
// at the figures measured on the commit of the model (docs/perception.md, "World scenarios");
// the targets that these do not meet are in docs/targets.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "tools/legs/world_figures.h"
#include "tools/world/scenario_loader.h"

namespace slammtt {
namespace {

struct Floors {
  const char* scenario;
  double max_range_m;
  double recall;
  double precision;
  double centre_median_m;
};

// Measured (pooled over seeds 1-20, every 10th scan; held-out seeds 21-40 in docs/perception.md):
// office within 4 m recall 0.861, precision 0.891, centre error median 0.016 m; office-hokuyo
// 0.710, 0.583, 0.097 m; corridor within 4 m 0.926, 0.801, 0.123 m (0.860 with
// person_single_leg_surface_clearance_m 0.2, 0.881 with person_separate_dropout_pieces too, both
// off by default; office and office-hokuyo unchanged by them). With
// person_hidden_leg_centre (off by default: it costs the estimator's office people MOTA):
// office 0.862 / 0.892 / 0.016 m, office-hokuyo 0.756 / 0.621 / 0.083 m, corridor 0.930 /
// 0.806 / 0.126 m. Before leg-like clusters
// within 0.025 m of a line of the scan became pieces of it: precision office 0.879,
// office-hokuyo 0.525, corridor 0.800 (recall the same). Before flat pieces between no-return
// beams made no person and max_leg_separation_m became 0.7: office 0.861 / 0.840,
// office-hokuyo 0.737 / 0.408 (its recall paid 0.027 for the longer pairs, which join legs of
// two people), corridor 0.810 / 0.563. Floors (ceilings for the centre error) a little beyond.
constexpr Floors kFloors[] = {
    {"office", 4.0, 0.84, 0.88, 0.03},
    {"office-hokuyo", 1e9, 0.69, 0.56, 0.11},
    {"corridor", 4.0, 0.90, 0.78, 0.14},
};

// The test's name in ctest: the scenario, not the bytes of the struct.
void PrintTo(const Floors& floors, std::ostream* out) { *out << floors.scenario; }

std::vector<uint64_t> Seeds() {
  std::vector<uint64_t> seeds;
  for (uint64_t s = 1; s <= 20; ++s) seeds.push_back(s);
  return seeds;
}

class WorldFiguresTest : public ::testing::TestWithParam<Floors> {};

TEST_P(WorldFiguresTest, PeopleAtOrAboveTheMeasuredFloors) {
  const Floors& f = GetParam();
  const Scenario scenario = LoadScenario(std::string(SLAMMTT_SOURCE_DIR) +
                                         "/config/scenarios/" + f.scenario + ".yaml");
  FeatureScoreOptions score;
  score.max_range_m = f.max_range_m;
  const WorldFigures w = MeasureWorldFigures(scenario, Seeds(), SegmenterOptions{}, 10, score);
  ASSERT_GT(w.pooled.people_truth, 100);
  std::vector<double> errors = w.pooled.centre_errors_m;
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  std::printf("%s: %lld scans, %lld people, recall %.4f, precision %.4f, centre median %.4f m, "
              "walls %.4f of %lld point features\n",
              f.scenario, static_cast<long long>(w.scans),
              static_cast<long long>(w.pooled.people_truth), w.pooled.PersonRecall(),
              w.pooled.PersonPrecision(), median, w.pooled.WallPointShare(),
              static_cast<long long>(w.pooled.point_features));
  EXPECT_GE(w.pooled.PersonRecall(), f.recall);
  EXPECT_GE(w.pooled.PersonPrecision(), f.precision);
  EXPECT_LE(median, f.centre_median_m);
  // False one-leg people that were their person's only feature of the scan: the person's legs
  // stood apart (a walker's trailing leg), so a centre from one leg could not be within 0.3 m.
  const std::vector<double>& lone = w.causes.false_one_leg_alone_farther_leg_m;
  std::vector<double> sorted_lone = lone;
  std::sort(sorted_lone.begin(), sorted_lone.end());
  std::printf("%s: %zu false one-leg people were their person's only feature; the person's "
              "farther leg from its centre: min %.3f, median %.3f m\n",
              f.scenario, lone.size(), sorted_lone.empty() ? 0.0 : sorted_lone.front(),
              sorted_lone.empty() ? 0.0 : sorted_lone[sorted_lone.size() / 2]);
  ASSERT_FALSE(sorted_lone.empty());
  EXPECT_GE(sorted_lone.front(), 0.3);  // measured: 0.310 (office), 0.313, 0.316
}

INSTANTIATE_TEST_SUITE_P(Scenarios, WorldFiguresTest, ::testing::ValuesIn(kFloors),
                         [](const ::testing::TestParamInfo<Floors>& param) {
                           std::string name = param.param.scenario;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace slammtt
