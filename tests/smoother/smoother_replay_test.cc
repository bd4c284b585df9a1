// slammtt-smoother's stage in slammtt-replay on s1-crossing seed 1 (docs/smoother.md, "In the
// stack"): a `smoother:` section or --smoother runs it, SMOOTHED_POSE at every scan and
// SMOOTHED_MAP exist, the output is the same bytes every run, the filter's outputs are those of
// a replay without the smoother, slammtt-eval scores the smoothed trajectory and map (the
// smoothed trajectory's shape better than the filter's), and slammtt-timing sees the stage.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

std::string Config() {
  return std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/s1-crossing.yaml";
}

std::map<std::string, std::vector<std::string>> Channels(const std::string& path) {
  std::map<std::string, std::vector<std::string>> channels;
  for (const LogEvent& e : testing::ReadLog(path)) {
    channels[e.channel].emplace_back(reinterpret_cast<const char*>(e.data.data()), e.data.size());
  }
  return channels;
}

// s1-crossing seed 1's world log at `path`; slammtt-world's exit status, its output in `out`.
int WriteWorldLog(const std::string& path, std::string* out) {
  return Shell(Bin("slammtt-world") + " --scenario s1-crossing --seed 1 --log " + path, out);
}

TEST(SmootherReplayTest, SmoothedTrajectoryAndMapAreDeterministicAndScored) {
  testing::TempDir dir;
  std::string out;
  ASSERT_EQ(WriteWorldLog(dir.File("world.lcm"), &out), 0) << out;
  {
    std::ofstream config(dir.File("smoother.yaml"));
    config << testing::FileBytes(Config()) << "smoother:\n  keyframe_interval_s: 0\n";
  }
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir.File("world.lcm") + " -o " +
                      dir.File("a.lcm") + " --config " + dir.File("smoother.yaml"),
                  &out),
            0)
      << out;
  EXPECT_NE(out.find("smoother: handled 961 messages"), std::string::npos) << out;
  // The flag runs it with the defaults too: the same bytes.
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir.File("world.lcm") + " -o " +
                      dir.File("b.lcm") + " --no-timing --smoother --config " + Config(),
                  &out),
            0)
      << out;
  const std::string a = testing::FileBytes(dir.File("a.lcm"));
  EXPECT_EQ(a, testing::FileBytes(dir.File("b.lcm")));
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir.File("world.lcm") + " -o " +
                      dir.File("filter.lcm") + " --no-timing --config " + Config(),
                  &out),
            0)
      << out;

  auto with = Channels(dir.File("a.lcm"));
  auto without = Channels(dir.File("filter.lcm"));
  EXPECT_EQ(with["SMOOTHED_POSE"].size(), 961u);
  EXPECT_EQ(with["SMOOTHER_INPUT"].size(), 961u);
  EXPECT_GE(with["SMOOTHED_MAP"].size(), 961u / 8);
  EXPECT_EQ(with["SMOOTHED_TRAJECTORY"].size(), with["SMOOTHED_MAP"].size());
  EXPECT_EQ(without.count("SMOOTHED_POSE"), 0u);
  for (const char* channel : {"POSE", "MAP", "TRACKS", "SMOOTHER_INPUT", "ESTIMATOR_STATUS"}) {
    EXPECT_TRUE(with[channel] == without[channel]) << channel;
  }

  ASSERT_EQ(Shell(Bin("slammtt-eval") + " " + dir.File("a.lcm") + " --config " + Config() +
                      " --json " + dir.File("report.json") + " --plots " + dir.File("plots"),
                  &out),
            0)
      << out;
  const nlohmann::json report =
      nlohmann::json::parse(testing::FileBytes(dir.File("report.json")));
  ASSERT_TRUE(report["smoothed_ate_rmse_m"].is_number()) << report.dump();
  ASSERT_TRUE(report["smoothed_landmark_rmse_m"].is_number());
  const double smoothed = report["smoothed_ate_rmse_m"].get<double>();
  // The smoothed trajectory's shape is better than the filter's (ATE after the best rigid
  // alignment; seed 1: 0.027 m against 0.045 m, better on every seed 1-30, docs/smoother.md),
  // and the smoothed trajectory far better than dead reckoning (0.77 m). Issue 14's target on the
  // ATE anchored at the first pose (no worse than the filter's) is open:
  // smoother_targets_open_test.
  EXPECT_LE(report["detail"]["smoothed_robot"]["aligned"]["ate_rmse_m"].get<double>(),
            report["detail"]["robot"]["aligned"]["ate_rmse_m"].get<double>());
  EXPECT_LT(smoothed, 0.5 * report["odometry_ate_rmse_m"].get<double>());
  EXPECT_LT(report["smoothed_landmark_rmse_m"].get<double>(), 0.5);
  EXPECT_GE(report["detail"]["smoothed_map"]["static_recall"].get<double>(), 0.9);
  // The final smoothed trajectory: every keyframe (every scan here) up to the last map's.
  ASSERT_TRUE(report["final_smoothed_ate_rmse_m"].is_number());
  EXPECT_GE(report["detail"]["final_smoothed_trajectory"]["per_scan"]["utime"].size(), 961u - 8u);
  EXPECT_LT(report["final_smoothed_ate_rmse_m"].get<double>(),
            0.5 * report["odometry_ate_rmse_m"].get<double>());
  const std::string trajectory = testing::FileBytes(dir.File("plots/trajectory.svg"));
  EXPECT_NE(trajectory.find("smoothed (ATE RMSE"), std::string::npos);

  ASSERT_EQ(Shell(Bin("slammtt-timing") + " " + dir.File("a.lcm.timing.lcm"), &out), 0) << out;
  for (const char* name : {"smoother", "smooth", "publish", "#keyframes", "#landmarks"}) {
    EXPECT_NE(out.find(name), std::string::npos) << name << "\n" << out;
  }
}

// The estimator's smoother_feedback (docs/smoother.md, "Feedback"): in replay the smoother's
// SMOOTHED_POSE and SMOOTHED_MAP go back to the estimator before the next scan, so the output is
// the same bytes every run, and the filter's outputs change (they follow the smoother). (About
// 15 s: three replays.)
TEST(SmootherReplayTest, FeedbackIsDeterministicAndMovesTheFilter) {
  testing::TempDir dir;
  std::string out;
  ASSERT_EQ(WriteWorldLog(dir.File("world.lcm"), &out), 0) << out;
  {
    std::string config = testing::FileBytes(Config());
    const std::string section = "estimator:\n";
    const size_t at = config.find(section);
    ASSERT_NE(at, std::string::npos);
    config.insert(at + section.size(), "  smoother_feedback: true\n");
    std::ofstream(dir.File("feedback.yaml")) << config << "smoother: {}\n";
  }
  for (const char* name : {"a.lcm", "b.lcm"}) {
    ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir.File("world.lcm") + " -o " +
                        dir.File(name) + " --no-timing --config " + dir.File("feedback.yaml"),
                    &out),
              0)
        << out;
  }
  EXPECT_EQ(testing::FileBytes(dir.File("a.lcm")), testing::FileBytes(dir.File("b.lcm")));
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir.File("world.lcm") + " -o " +
                      dir.File("without.lcm") + " --no-timing --stage estimator --config " +
                      dir.File("feedback.yaml"),
                  &out),
            0)
      << out;
  auto with = Channels(dir.File("a.lcm"));
  auto without = Channels(dir.File("without.lcm"));
  EXPECT_EQ(with["POSE"].size(), without["POSE"].size());
  EXPECT_EQ(with["SMOOTHED_POSE"].size(), 961u);
  // Without the smoother's stage nothing comes back: the filter of a replay without feedback.
  EXPECT_EQ(without.count("SMOOTHED_POSE"), 0u);
  EXPECT_FALSE(with["POSE"] == without["POSE"]);
  // Before the first SMOOTHED_MAP (the 8th keyframe) nothing has been fed back.
  for (size_t k = 0; k < 8; ++k) EXPECT_EQ(with["POSE"][k], without["POSE"][k]) << k;
}

}  // namespace
}  // namespace slammtt
