// Issue 13, item 5: a robot that publishes no ODOMETRY moves by the static structure
// (scan_alignment.h), so that the scenery is not taken for movers. office and corridor, seeds
// 1-20, replayed with `slammtt-replay --drop-channel ODOMETRY` and scored by slammtt-eval
// (docs/targets.md). Built twice: without NO_ODOMETRY_TARGETS_OPEN the targets the estimator
// meets (label `target`), with it the ones it does not meet yet (label `target_open`), asserted
// just as the issue states them: no more than 1 confirmed mover per minute that is not a person
// (slammtt-eval's non_person_movers_per_minute at the 0.75 m people threshold), and ATE <= 3x
// the ATE of the same seed with odometry.
#include <string>

#include "tests/estimator/target_figures.h"

namespace slammtt {
namespace {

using testing::Number;

constexpr int kFirstSeed = 1;
constexpr int kLastSeed = 20;

const testing::PipelineRun& WithOdometry(const char* scenario, int seed) {
  return testing::SharedPipelineRunner().Run(scenario, seed, "ml_ransac");
}

const testing::PipelineRun& WithoutOdometry(const char* scenario, int seed) {
  return testing::SharedPipelineRunner().Run(scenario, seed, "ml_ransac", {},
                                             "--drop-channel ODOMETRY");
}

[[maybe_unused]] void ExpectAteWithinThreeTimesOdometrys(const char* scenario) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE(std::string(scenario) + " seed " + std::to_string(seed));
    const double with = Number(WithOdometry(scenario, seed).report, "ate_rmse_m");
    const double without = Number(WithoutOdometry(scenario, seed).report, "ate_rmse_m");
    std::cout << scenario << " seed " << seed << ": ATE " << without << " m without odometry, "
              << with << " m with\n";
    EXPECT_LE(without, 3.0 * with);
  }
}

[[maybe_unused]] void ExpectAtMostOneNonPersonMoverPerMinute(const char* scenario) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE(std::string(scenario) + " seed " + std::to_string(seed));
    const nlohmann::json people = testing::SharedPipelineRunner().Rescore(
        WithoutOdometry(scenario, seed), "--match-threshold-m 0.75");
    const double per_minute = Number(people, "non_person_movers_per_minute");
    std::cout << scenario << " seed " << seed << ": " << per_minute
              << " movers that are no person per minute without odometry\n";
    EXPECT_LE(per_minute, 1.0);
  }
}

#ifdef NO_ODOMETRY_TARGETS_OPEN

TEST(NoOdometryOpenTargetsTest, OfficeAtMostOneNonPersonMoverPerMinute) {
  ExpectAtMostOneNonPersonMoverPerMinute("office");
}

TEST(NoOdometryOpenTargetsTest, CorridorAtMostOneNonPersonMoverPerMinute) {
  ExpectAtMostOneNonPersonMoverPerMinute("corridor");
}

TEST(NoOdometryOpenTargetsTest, OfficeAteWithinThreeTimesTheAteWithOdometry) {
  ExpectAteWithinThreeTimesOdometrys("office");
}

#else

TEST(NoOdometryTargetsTest, CorridorAteWithinThreeTimesTheAteWithOdometry) {
  ExpectAteWithinThreeTimesOdometrys("corridor");
}

#endif

}  // namespace
}  // namespace slammtt
