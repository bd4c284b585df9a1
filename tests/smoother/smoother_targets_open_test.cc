// Issue 14's targets for the smoother on the paper's scenario that are not met yet
// (docs/targets.md, "Smoother in the stack"; label target_open, left out of the default run):
// on s1-crossing seeds 1-30 the smoothed ATE and landmark RMSE no worse than the filter's, and
// seed 7's smoothed ATE at most 0.1 m. Each seed: slammtt-world -> slammtt-replay --smoother ->
// slammtt-eval (about 6 s a seed), the figures scripts/measure-smoother.sh prints.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

nlohmann::json SmoothedReport(int seed, const testing::TempDir& dir) {
  const std::string world = dir.File("world" + std::to_string(seed) + ".lcm");
  const std::string replay = dir.File("replay" + std::to_string(seed) + ".lcm");
  const std::string report = dir.File("report" + std::to_string(seed) + ".json");
  const std::string config = std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/s1-crossing.yaml";
  std::string out;
  EXPECT_EQ(Shell(Bin("slammtt-world") + " --quiet --scenario s1-crossing --seed " +
                      std::to_string(seed) + " --log " + world,
                  &out),
            0)
      << out;
  EXPECT_EQ(Shell(Bin("slammtt-replay") + " --quiet --no-timing --smoother " + world + " -o " +
                      replay + " --config " + config,
                  &out),
            0)
      << out;
  EXPECT_EQ(Shell(Bin("slammtt-eval") + " --quiet " + replay + " --config " + config +
                      " --json " + report,
                  &out),
            0)
      << out;
  return nlohmann::json::parse(testing::FileBytes(report));
}

TEST(SmootherTargetsOpenTest, SmoothedNeverWorseThanTheFilterOnSeeds1To30AndSeed7Within10Cm) {
  testing::TempDir dir;
  for (int seed = 1; seed <= 30; ++seed) {
    const nlohmann::json report = SmoothedReport(seed, dir);
    ASSERT_TRUE(report["smoothed_ate_rmse_m"].is_number()) << "seed " << seed;
    ASSERT_TRUE(report["smoothed_landmark_rmse_m"].is_number()) << "seed " << seed;
    const double smoothed_ate = report["smoothed_ate_rmse_m"].get<double>();
    EXPECT_LE(smoothed_ate, report["ate_rmse_m"].get<double>()) << "seed " << seed;
    EXPECT_LE(report["smoothed_landmark_rmse_m"].get<double>(),
              report["landmark_rmse_m"].get<double>())
        << "seed " << seed;
    if (seed == 7) {
      EXPECT_LE(smoothed_ate, 0.1);
    }
  }
}

}  // namespace
}  // namespace slammtt
