// The targets of the walls as line landmarks (issue 13, item 1) on the scenarios with walls,
// seeds 1-20, scored by slammtt-eval (docs/evaluation.md, "Line landmarks"; docs/targets.md).
// Each TEST is one target; a run (world -> replay with the segmenter -> eval) is made once per
// scenario and seed and shared by the TESTs, which run in one process (ONE_PROCESS in
// CMakeLists.txt). Built twice: without LINE_TARGETS_OPEN the targets the estimator meets (label
// `target`), with it the ones it does not meet yet (label `target_open`), asserted just as the
// issue states them.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/child_process.h"

#include "tests/estimator/target_figures.h"

namespace slammtt {
namespace {

using testing::Number;
using testing::TargetRun;

constexpr int kFirstSeed = 1;
constexpr int kLastSeed = 20;

const testing::PipelineRun& ScenarioRun(const char* scenario, int seed) {
  return TargetRun(scenario, seed, "ml_ransac");
}

[[maybe_unused]] double FinalHeadingErrorDeg(const nlohmann::json& report) {
  return std::abs(report["detail"]["robot"]["final_heading_error_rad"].get<double>()) * 180.0 /
         M_PI;
}

const nlohmann::json& Lines(const nlohmann::json& report) {
  return report["detail"]["map"]["lines"];
}

#ifndef LINE_TARGETS_OPEN

TEST(OfficeLineTargetsTest, RobotAteAtMost005m) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    EXPECT_LE(Number(ScenarioRun("office", seed).report, "ate_rmse_m"), 0.05);
  }
}

TEST(OfficeLineTargetsTest, FinalHeadingErrorAtMost1Degree) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    EXPECT_LE(FinalHeadingErrorDeg(ScenarioRun("office", seed).report), 1.0);
  }
}

TEST(CorridorLineTargetsTest, RobotAteAtMost015m) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("corridor seed " + std::to_string(seed));
    EXPECT_LE(Number(ScenarioRun("corridor", seed).report, "ate_rmse_m"), 0.15);
  }
}

// The walls are in the map as lines: most line landmarks lie on a true surface.
TEST(OfficeLineTargetsTest, LineLandmarksLieOnTheWalls) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    const nlohmann::json& lines = Lines(ScenarioRun("office", seed).report);
    ASSERT_TRUE(lines.is_object());
    EXPECT_GE(lines["matched"].get<double>(), 0.8 * lines["lines"].get<double>());
    EXPECT_GE(lines["matched"].get<int>(), 20);
  }
}

// The office with its laser turned 30 degrees left on the robot (world: laser.mount_yaw_deg),
// seed 1, through world -> segmenter -> estimator -> eval; `estimator_yaw_deg` is what the
// estimator is told (sensor_yaw_deg).
nlohmann::json RotatedLaserRun(double estimator_yaw_deg) {
  static testing::TempDir directory("slammtt-rotated");
  const std::string source = std::string(SLAMMTT_SOURCE_DIR);
  std::ifstream scenario_in(source + "/config/scenarios/office.yaml");
  std::stringstream scenario_text;
  scenario_text << scenario_in.rdbuf();
  std::string scenario = scenario_text.str();
  const std::string mount = "  mount_b_m: 0.0\n";
  const size_t at = scenario.find(mount);
  if (at == std::string::npos) throw std::runtime_error("office.yaml: no laser.mount_b_m");
  scenario.insert(at + mount.size(), "  mount_yaw_deg: 30\n");
  const std::string scenario_path = directory.File("office-rotated.yaml");
  std::ofstream(scenario_path) << scenario;
  std::ifstream config_in(source + "/estimator/config/office.yaml");
  std::stringstream config;
  config << config_in.rdbuf() << "  sensor_yaw_deg: " << estimator_yaw_deg << "\n";
  const std::string tag = std::to_string(static_cast<int>(estimator_yaw_deg));
  const std::string config_path = directory.File("office-rotated-" + tag + ".yaml");
  std::ofstream(config_path) << config.str();
  const std::string world = directory.File("office-rotated.lcm");
  const std::string out = directory.File("office-rotated-" + tag + ".out.lcm");
  const std::string report = directory.File("office-rotated-" + tag + ".json");
  const std::string bin = SLAMMTT_BIN_DIR;
  std::string output;
  const std::string command =
      "{ [ -f " + world + " ] || " + bin + "/slammtt-world --quiet --scenario " + scenario_path +
      " --seed 1 --log " + world + "; } && " + bin + "/slammtt-replay --quiet " + world +
      " -o " + out + " --no-timing --config " + config_path +
      " --stage segmenter --stage estimator && " + bin + "/slammtt-eval --quiet " + out +
      " --json " + report + " > /dev/null";
  if (testing::Shell(command, &output) != 0) throw std::runtime_error(command + "\n" + output);
  std::ifstream json(report);
  return nlohmann::json::parse(json);
}

TEST(RotatedLaserTest, TheEstimatorTakesTheMountYaw) {
  const nlohmann::json told = RotatedLaserRun(30.0);
  EXPECT_LE(Number(told, "ate_rmse_m"), 0.05);
  EXPECT_LE(FinalHeadingErrorDeg(told), 1.0);
  EXPECT_EQ(Lines(told)["matched"], Lines(told)["lines"]);
  // Not told, its map is turned by the yaw against the robot's odometry: the walls disagree
  // with the motion and the pose is lost.
  const nlohmann::json not_told = RotatedLaserRun(0.0);
  EXPECT_GT(Number(not_told, "ate_rmse_m"), 5.0 * Number(told, "ate_rmse_m"));
}

TEST(OfficeLineTargetsTest, NoWallInTheStaticPointMap) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    const nlohmann::json& lines = Lines(ScenarioRun("office", seed).report);
    EXPECT_EQ(lines["point_landmarks_on_walls"].get<int>(), 0);
  }
}

// The angle error of the line landmarks, the median over a run's matched landmarks.
TEST(OfficeLineTargetsTest, LineLandmarkAngleErrorMedianAtMost1Degree) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    const nlohmann::json& lines = Lines(ScenarioRun("office", seed).report);
    EXPECT_LE(lines["angle_error_deg"]["median"].get<double>(), 1.0);
  }
}

#else

// The strict reading of the angle target: every matched line landmark within 1 degree.
TEST(OfficeLineTargetsOpenTest, EveryLineLandmarkAngleErrorAtMost1Degree) {
  for (int seed = kFirstSeed; seed <= kLastSeed; ++seed) {
    SCOPED_TRACE("office seed " + std::to_string(seed));
    const nlohmann::json& lines = Lines(ScenarioRun("office", seed).report);
    EXPECT_LE(lines["angle_error_deg"]["max"].get<double>(), 1.0);
  }
}

#endif

}  // namespace
}  // namespace slammtt
