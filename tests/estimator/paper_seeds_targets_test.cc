// Issue 13, "Targets that generalise": the s2-lobby, s3-no-static and rplidar-a2 targets hold
// on seeds 1-30 as the s1 targets must, that is on at least 29 of the 30 seeds (the issue: "the
// current s1 targets ... on at least 29 of 30 seeds ... s2-lobby, s3-no-static, rplidar-a2
// targets on seeds 1-30 likewise"). estimator_targets_test asserts the same targets on every
// one of seeds 1-5; docs/targets.md gives the figures per seed. Label `target` (default run).
#include <string>
#include <vector>

#include "tests/estimator/target_figures.h"

namespace slammtt {
namespace {

using testing::Number;
using testing::Print;
using testing::TargetRun;

constexpr int kFirstSeed = 1;
constexpr int kLastSeed = 30;
constexpr int kSeedsThatMustHold = 29;

// Seeds of 1-30 on which `holds` is false, printed beside the count.
template <typename Holds>
std::vector<int> SeedsMissed(const std::string& scenario, Holds holds) {
  std::vector<int> missed;
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    const testing::PipelineRun& ml = TargetRun(scenario, seed, "ml_ransac");
    Print(scenario + " seed " + std::to_string(seed) + " ml_ransac", ml);
    if (!holds(seed, ml)) missed.push_back(seed);
  }
  std::cout << scenario << ": targets missed on " << missed.size() << " of "
            << kLastSeed - kFirstSeed + 1 << " seeds";
  for (int seed : missed) std::cout << " " << seed;
  std::cout << "\n";
  return missed;
}

int SeedsHeld(const std::vector<int>& missed) {
  return kLastSeed - kFirstSeed + 1 - static_cast<int>(missed.size());
}

TEST(PaperScenariosOnThirtySeedsTest, S2LobbyMotaAndTenTimesFewerHypotheses) {
  const std::vector<int> missed =
      SeedsMissed("s2-lobby", [](int seed, const testing::PipelineRun& ml) {
        const testing::PipelineRun& all = TargetRun("s2-lobby", seed, "ransac_all_pairs");
        return Number(ml.report, "mota") >= 0.85 && 10 * ml.hypotheses <= all.hypotheses;
      });
  EXPECT_GE(SeedsHeld(missed), kSeedsThatMustHold);
}

TEST(PaperScenariosOnThirtySeedsTest, S3NoStaticMotaAndNoWorseThanOdometry) {
  const std::vector<int> missed =
      SeedsMissed("s3-no-static", [](int, const testing::PipelineRun& ml) {
        return Number(ml.report, "mota") >= 0.9 &&
               Number(ml.report, "ate_rmse_m") <= 1.1 * Number(ml.report, "odometry_ate_rmse_m");
      });
  EXPECT_GE(SeedsHeld(missed), kSeedsThatMustHold);
}

TEST(PaperScenariosOnThirtySeedsTest, RplidarA2Mota) {
  const std::vector<int> missed =
      SeedsMissed("rplidar-a2", [](int, const testing::PipelineRun& ml) {
        return Number(ml.report, "mota") >= 0.85;
      });
  EXPECT_GE(SeedsHeld(missed), kSeedsThatMustHold);
}

}  // namespace
}  // namespace slammtt
