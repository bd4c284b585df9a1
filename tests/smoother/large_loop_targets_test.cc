// Issue 14, "Large loop": on the large-loop family (1000 point landmarks over a 365 m loop with
// odometry drift, seeds 1-10) the smoothed ATE (live and final) is at most 0.2 m and the static
// recall at least 0.95 (the smoother's map: the smoother keeps every landmark). Label target_open: not met yet
// (docs/targets.md, "Smoother in the stack"; figures by scripts/measure-large-loop.py). The
// cost target (per-scan p99 <= 10 ms) is measured by that script, never by a timed test.
// About a minute per seed.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

class LargeLoopTargetsTest : public ::testing::TestWithParam<int> {};

TEST_P(LargeLoopTargetsTest, SmoothedAteAndStaticRecall) {
  const int seed = GetParam();
  const std::string config =
      std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/large-loop.yaml";
  testing::TempDir dir;
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-world") + " --quiet --scenario large-loop --seed " +
                      std::to_string(seed) + " --log " + dir.File("world.lcm"),
                  &out),
            0)
      << out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --quiet --no-timing " + dir.File("world.lcm") +
                      " -o " + dir.File("run.lcm") + " --config " + config,
                  &out),
            0)
      << out;
  ASSERT_EQ(Shell(Bin("slammtt-eval") + " --quiet " + dir.File("run.lcm") + " --config " +
                      config + " --json " + dir.File("report.json"),
                  &out),
            0)
      << out;
  const nlohmann::json report =
      nlohmann::json::parse(testing::FileBytes(dir.File("report.json")));
  ASSERT_TRUE(report["smoothed_ate_rmse_m"].is_number()) << "no smoother output";
  // Both the live SMOOTHED_POSE and the final smoothed trajectory (every keyframe as estimated
  // at the end, after the loop closed): docs/evaluation.md, "The smoother".
  EXPECT_LE(report["smoothed_ate_rmse_m"].get<double>(), 0.2) << "seed " << seed;
  ASSERT_TRUE(report["final_smoothed_ate_rmse_m"].is_number()) << "no SMOOTHED_TRAJECTORY";
  EXPECT_LE(report["final_smoothed_ate_rmse_m"].get<double>(), 0.2) << "seed " << seed;
  EXPECT_GE(report["detail"]["smoothed_map"]["static_recall"].get<double>(), 0.95)
      << "seed " << seed;
}

INSTANTIATE_TEST_SUITE_P(Seeds, LargeLoopTargetsTest, ::testing::Range(1, 11));

}  // namespace
}  // namespace slammtt
