// The targets of the estimator's issue that the estimator does not meet on every seed yet
// (label `target_open`, left out of the default run; docs/targets.md gives the measured figures
// and why). They assert the figures exactly: when one passes on every seed, its TEST
// moves to targets_test.cc (label `target`).
#include <algorithm>
#include <string>
#include <vector>

#include "tests/estimator/target_figures.h"

namespace slammtt {
namespace {

using testing::kTargetSeeds;
using testing::Number;
using testing::Print;
using testing::TargetRun;

TEST(S1CrossingOpenTargetsTest, RobotAteFiveTimesLowerThanBaselineA) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("s1-crossing", seed, "ml_ransac");
    const testing::PipelineRun& nn = TargetRun("s1-crossing", seed, "static_nn");
    Print("s1-crossing seed " + std::to_string(seed) + " ml_ransac", ml);
    Print("s1-crossing seed " + std::to_string(seed) + " static_nn", nn);
    EXPECT_LE(5.0 * Number(ml.report, "ate_rmse_m"), Number(nn.report, "ate_rmse_m"))
        << "robot ATE not 5 times lower than the static-world baseline";
  }
}

// Issue 13: the s1 targets on at least 29 of seeds 1-30, and the median ATE <= 0.1 m.
TEST(S1CrossingOpenTargetsTest, S1TargetsHoldOn29Of30SeedsAndMedianAteIsAtMost10Cm) {
  int met = 0;
  std::vector<double> ate;
  for (int seed = 1; seed <= 30; ++seed) {
    const testing::PipelineRun& run = TargetRun("s1-crossing", seed, "ml_ransac");
    Print("s1-crossing seed " + std::to_string(seed), run);
    ate.push_back(Number(run.report, "ate_rmse_m"));
    met += Number(run.report, "id_switches") == 0 && Number(run.report, "mota") >= 0.95 &&
                   ate.back() <= 0.3 && Number(run.report, "movers_in_static_map") == 0
               ? 1
               : 0;
  }
  std::sort(ate.begin(), ate.end());
  EXPECT_GE(met, 29) << "s1 targets met on " << met << " of 30 seeds";
  EXPECT_LE(0.5 * (ate[14] + ate[15]), 0.1) << "median ATE over seeds 1-30";
}

// Issue 13: office, seeds 1-20: person MOTA >= 0.85 at a 0.75 m match threshold with standing
// people counted as people (slammtt-eval's people_mota), identity switches <= 2 per person per
// minute (median), no person in the static point map.
TEST(PeopleOpenTargetsTest, OfficePeopleMota) {
  std::vector<double> switches_per_person_minute;
  for (int seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    const testing::PipelineRun& run = TargetRun("office", seed, "ml_ransac");
    const nlohmann::json people =
        testing::SharedPipelineRunner().Rescore(run, "--match-threshold-m 0.75");
    std::cout << "office seed " << seed << ": people_mota " << people["people_mota"].dump()
              << " people_id_switches " << people["people_id_switches"].dump()
              << " movers_in_static_map " << people["movers_in_static_map"].dump() << "\n";
    EXPECT_GE(Number(people, "people_mota"), 0.85);
    EXPECT_EQ(Number(people, "movers_in_static_map"), 0) << "a person in the static map";
    // Six people over the 120 s run (config/scenarios/office.yaml): switches per person-minute.
    switches_per_person_minute.push_back(Number(people, "people_id_switches") / (6 * 2.0));
  }
  std::sort(switches_per_person_minute.begin(), switches_per_person_minute.end());
  EXPECT_LE(0.5 * (switches_per_person_minute[9] + switches_per_person_minute[10]), 2.0);
}

// Issue 13: corridor, seeds 1-20: person MOTA >= 0.8.
TEST(PeopleOpenTargetsTest, CorridorPeopleMota) {
  for (int seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("corridor seed " + std::to_string(seed));
    const testing::PipelineRun& run = TargetRun("corridor", seed, "ml_ransac");
    std::cout << "corridor seed " << seed << ": people_mota "
              << run.report["people_mota"].dump() << "\n";
    EXPECT_GE(Number(run.report, "people_mota"), 0.8);
  }
}

}  // namespace
}  // namespace slammtt
