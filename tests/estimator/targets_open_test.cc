// The targets of the estimator's issue that the estimator does not meet on every seed yet
// (label `target_open`, left out of the default run; docs/targets.md gives the measured figures
// and why). They assert the figures exactly: when one passes on every seed, its TEST
// moves to targets_test.cc (label `target`).
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

}  // namespace
}  // namespace slammtt
