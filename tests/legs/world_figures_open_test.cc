// The issue-11 targets (Measure) on the world's legged-people scenarios that are not met yet
// (label target_open; tools/legs/world_figures.h, seeds 1-20, every 10th scan): person recall
// and precision >= 0.9 at 0.35 degrees (office-hokuyo: 0.710 / 0.525), >= 0.8 / 0.9 at 0.9
// degrees within 4 m (office 0.861 / 0.879, corridor 0.926 / 0.800: precision open), centre
// error median <= 0.08 m (office-hokuyo 0.097 m, corridor 0.123 m: the world's walking body
// leads the midpoint of its legs by about 0.12 m, docs/perception.md, "World scenarios").
// legs_world_figures_test holds the measured floors.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "tools/legs/world_figures.h"
#include "tools/world/scenario_loader.h"

namespace slammtt {
namespace {

struct Targets {
  const char* scenario;
  double max_range_m;
  double recall;
  double precision;
};

constexpr Targets kTargets[] = {
    {"office", 4.0, 0.8, 0.9},
    {"office-hokuyo", 1e9, 0.9, 0.9},
    {"corridor", 4.0, 0.8, 0.9},
};

void PrintTo(const Targets& targets, std::ostream* out) { *out << targets.scenario; }

class WorldTargetsTest : public ::testing::TestWithParam<Targets> {};

TEST_P(WorldTargetsTest, IssueTargets) {
  const Targets& t = GetParam();
  const Scenario scenario = LoadScenario(std::string(SLAMMTT_SOURCE_DIR) +
                                         "/config/scenarios/" + t.scenario + ".yaml");
  FeatureScoreOptions score;
  score.max_range_m = t.max_range_m;
  std::vector<uint64_t> seeds;
  for (uint64_t s = 1; s <= 20; ++s) seeds.push_back(s);
  const WorldFigures w = MeasureWorldFigures(scenario, seeds, SegmenterOptions{}, 10, score);
  ASSERT_GT(w.pooled.people_truth, 100);
  std::vector<double> errors = w.pooled.centre_errors_m;
  std::sort(errors.begin(), errors.end());
  EXPECT_GE(w.pooled.PersonRecall(), t.recall);
  EXPECT_GE(w.pooled.PersonPrecision(), t.precision);
  EXPECT_LE(errors[errors.size() / 2], 0.08);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, WorldTargetsTest, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<Targets>& param) {
                           std::string name = param.param.scenario;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace slammtt
