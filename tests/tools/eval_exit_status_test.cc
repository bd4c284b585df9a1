// slammtt-eval tells the truth in its exit status and its report (issue 15 item 6): 0 when every
// headline figure was scored; 1, one line and no report when nothing can be scored (no
// GROUND_TRUTH, an empty file, a corrupt log); 2 for a bad command line or configuration; 3 when
// the report is written but a headline figure is withheld, with a machine-readable warning (POSE
// at too few ground-truth scans, TRACKS at too few). A truncated final event is a warning in the
// report. Before: the first two exited 0, the ATE of 3 poses out of 100 was the headline, MOTA 0
// was the headline when TRACKS matched no scan, the truncation warning was on stderr only, and a
// configuration error exited 1.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::ProcessResult;

const std::string kEval = std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval";

slammtt_msgs::ground_truth_t Truth(int64_t t, int k) {
  slammtt_msgs::ground_truth_t g{};
  g.utime = t;
  g.robot_x_m = 0.1 * k;
  slammtt_msgs::object_truth_t o{};
  o.id = 1;
  o.x_m = 3.0;
  o.y_m = 0.5 * k;
  o.vy_mps = 4.0;
  o.radius_m = 0.2;
  o.object_class = slammtt_msgs::object_truth_t::CLASS_MOVING;
  o.visible = 1;
  o.beams_on_object = 5;
  g.objects.push_back(o);
  g.num_objects = 1;
  return g;
}

// 100 ground-truth scans with a mover; POSE finite at `finite_poses` of them (NaN, rejected, at
// the rest); TRACKS following the mover, `tracks_offset_us` after each scan.
void WriteRun(const std::string& path, int finite_poses, int64_t tracks_offset_us) {
  LogWriter log(path);
  for (int k = 0; k < 100; ++k) {
    const int64_t t = 1000000 + 125000 * k;
    log.WriteMessage(t, "GROUND_TRUTH", Truth(t, k));
    slammtt_msgs::pose_t pose{};
    pose.utime = t;
    pose.x_m = k < finite_poses ? 0.1 * k : std::numeric_limits<double>::quiet_NaN();
    log.WriteMessage(t, "POSE", pose);
    slammtt_msgs::tracks_t tracks{};
    tracks.utime = t + tracks_offset_us;
    slammtt_msgs::track_t track{};
    track.id = 7;
    track.x_m = 3.0;
    track.y_m = 0.5 * k;
    track.vy_mps = 4.0;
    track.object_class = slammtt_msgs::track_t::CLASS_MOVING;
    track.confirmed = 1;
    tracks.tracks.push_back(track);
    tracks.num_tracks = 1;
    log.WriteMessage(t, "TRACKS", tracks);
  }
  log.Commit();
}

class EvalExitStatusTest : public ::testing::Test {
 protected:
  ProcessResult Eval(const std::string& log, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {kEval, log, "--json", dir_.File("report.json")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    std::remove(dir_.File("report.json").c_str());
    return testing::RunProcess(argv, dir_.path(), 60000);
  }
  nlohmann::json Report() {
    return nlohmann::json::parse(testing::FileBytes(dir_.File("report.json")));
  }
  static std::vector<std::string> WarningCodes(const nlohmann::json& report) {
    std::vector<std::string> codes;
    for (const auto& w : report.at("warnings")) codes.push_back(w.at("code"));
    return codes;
  }
  testing::TempDir dir_;
};

TEST_F(EvalExitStatusTest, AFullyScoredRunExitsZeroWithoutWarnings) {
  WriteRun(dir_.File("run.lcm"), 100, 0);
  const ProcessResult r = Eval(dir_.File("run.lcm"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Report();
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
  EXPECT_TRUE(j["ate_rmse_m"].is_number());
  EXPECT_TRUE(j["mota"].is_number());
}

TEST_F(EvalExitStatusTest, NothingToScoreIsAnErrorWithoutAReport) {
  {
    LogWriter log(dir_.File("no-truth.lcm"));
    slammtt_msgs::odometry_t odometry{};
    for (int k = 0; k < 50; ++k) {
      odometry.utime = 1000000 + 125000 * k;
      log.WriteMessage(odometry.utime, "ODOMETRY", odometry);
    }
    log.Commit();
  }
  testing::WriteFileBytes(dir_.File("empty.lcm"), "");
  for (const char* name : {"no-truth.lcm", "empty.lcm"}) {
    const ProcessResult r = Eval(dir_.File(name));
    EXPECT_EQ(r.exit_code, 1) << name << ": " << r.err;
    EXPECT_NE(r.err.find(dir_.File(name) + ": no GROUND_TRUTH: nothing can be scored; no report "
                                           "written"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(testing::FileExists(dir_.File("report.json"))) << name;
  }
}

TEST_F(EvalExitStatusTest, AnAteOfFewPosesIsNoHeadline) {
  WriteRun(dir_.File("few.lcm"), 3, 0);
  const ProcessResult r = Eval(dir_.File("few.lcm"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const nlohmann::json j = Report();
  EXPECT_TRUE(j["ate_rmse_m"].is_null());
  EXPECT_TRUE(j["detail"]["robot"]["ate_rmse_m"].is_number());  // still in the detail
  EXPECT_EQ(WarningCodes(j), std::vector<std::string>{"pose_coverage"});
  EXPECT_NE(j["warnings"][0]["message"].get<std::string>().find("3 of 100"), std::string::npos)
      << j["warnings"];
  EXPECT_NE(r.out.find("warning: "), std::string::npos) << r.out;
}

TEST_F(EvalExitStatusTest, TracksMatchingNoScanAreNoMota) {
  WriteRun(dir_.File("off.lcm"), 100, 1);  // every TRACKS 1 us after its scan
  const ProcessResult r = Eval(dir_.File("off.lcm"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const nlohmann::json j = Report();
  for (const char* key : {"mota", "motp_m", "ospa_mean_m", "gospa_mean_m", "id_switches",
                          "fragmentations", "idf1", "hota"}) {
    EXPECT_TRUE(j[key].is_null()) << key << " = " << j[key];
  }
  EXPECT_TRUE(j["ate_rmse_m"].is_number());
  EXPECT_EQ(WarningCodes(j), std::vector<std::string>{"tracks_coverage"});
}

TEST_F(EvalExitStatusTest, ATruncatedLogIsAWarningInTheReport) {
  WriteRun(dir_.File("run.lcm"), 100, 0);
  const std::string bytes = testing::FileBytes(dir_.File("run.lcm"));
  testing::WriteFileBytes(dir_.File("cut.lcm"), bytes.substr(0, bytes.size() - 10));
  const ProcessResult r = Eval(dir_.File("cut.lcm"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Report();
  EXPECT_EQ(WarningCodes(j), std::vector<std::string>{"log_truncated"});
  EXPECT_NE(j["warnings"][0]["message"].get<std::string>().find("truncated final event"),
            std::string::npos);
}

TEST_F(EvalExitStatusTest, ConfigurationErrorsExitTwo) {
  WriteRun(dir_.File("run.lcm"), 100, 0);
  std::ofstream(dir_.File("bad.yaml")) << "eval:\n  bogus: 1\n";
  std::ofstream(dir_.File("range.yaml")) << "eval:\n  gospa_alpha: 3\n";
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--config", dir_.File("bad.yaml")},
        std::vector<std::string>{"--config", dir_.File("range.yaml")},
        std::vector<std::string>{"--config", dir_.File("missing.yaml")},
        std::vector<std::string>{"--min-beams", "0"}}) {
    const ProcessResult r = Eval(dir_.File("run.lcm"), extra);
    EXPECT_EQ(r.exit_code, 2) << extra[0] << " " << extra[1] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(testing::FileExists(dir_.File("report.json")));
  }
}

}  // namespace
}  // namespace slammtt
