// slammtt-eval on a hand-built log whose every figure is computed by hand below.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "tests/tools/log_test_util.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/eval/report_json.h"
#include "tools/plots/eval_plots.h"

namespace slammtt {
namespace {

constexpr int64_t kT0 = 1000000;
constexpr int64_t kScanUs = 125000;
constexpr int kScans = 5;
using Obj = slammtt_msgs::object_truth_t;
using Trk = slammtt_msgs::track_t;

int64_t ScanTime(int k) { return kT0 + k * kScanUs; }

// The estimator's map frame: truth point (X, Y) = (2 + py, 3 - px) for a map point (px, py),
// i.e. the map frame sits at (2, 3) turned by -90 degrees in the truth frame.
Eigen::Vector2d ToMap(double x, double y) { return Eigen::Vector2d(3.0 - y, x - 2.0); }

Obj Object(int64_t id, double x, double y, bool moving, bool visible) {
  Obj o{};
  o.id = id;
  o.x_m = x;
  o.y_m = y;
  o.radius_m = 0.25;
  o.object_class = moving ? Obj::CLASS_MOVING : Obj::CLASS_STATIC;
  o.beams_on_object = visible ? 5 : 0;
  o.visible = visible;
  return o;
}

Trk Track(int64_t id, double truth_x, double truth_y, int8_t cls, bool confirmed = true) {
  Trk t{};
  t.id = id;
  const Eigen::Vector2d p = ToMap(truth_x, truth_y);
  t.x_m = p.x();
  t.y_m = p.y();
  t.covariance[0] = t.covariance[5] = 0.04;
  t.object_class = cls;
  t.confirmed = confirmed;
  t.hits = 3;
  return t;
}

// Truth (5 scans): the robot drives along +x from (2, 3); static S1 (5, 5) always visible, S2
// (10, -5) visible at scan 0 only, S3 (20, 20) never; mover M1 walks (2 + k, 6), always visible;
// mover M2 walks (8, k), invisible at scan 2.
// Estimator: POSE exact but for 0.3 m at scan 3 and +0.1 rad at scan 4. Tracks: M1 by 100
// (0.3 m off) then by 102 at scan 4 (an identity switch); M2 by 101 except scan 3 (a miss, and
// a fragmentation when 101 returns at scan 4), 101 coasting on the invisible M2 at scan 2 (don't
// care); S1 by 200, undecided at scan 0 then static; an unconfirmed track (ignored); a false
// moving track 400 at scan 3.
// Odometry at 8 Hz, half a scan out of phase, in the base's frame, drifting 0.2 m in y per scan.
void WriteHandBuiltLog(const std::string& path, bool with_estimator) {
  LogWriter log(path);
  for (int k = 0; k <= kScans; ++k) {
    slammtt_msgs::odometry_t odo{};
    odo.utime = kT0 - kScanUs / 2 + k * kScanUs;
    odo.sequence = k;
    const double s = static_cast<double>(odo.utime - kT0) / kScanUs;  // scans since the first
    odo.x_m = s;
    odo.y_m = 0.2 * s;
    log.WriteMessage(odo.utime, "ODOMETRY", odo);
  }
  for (int k = 0; k < kScans; ++k) {
    const int64_t t = ScanTime(k);
    slammtt_msgs::ground_truth_t gt{};
    gt.utime = t;
    gt.robot_x_m = 2.0 + k;
    gt.robot_y_m = 3.0;
    gt.robot_linear_mps = 8.0;
    gt.objects = {Object(1, 5, 5, false, true), Object(2, 10, -5, false, k == 0),
                  Object(3, 20, 20, false, false), Object(10, 2.0 + k, 6, true, true),
                  Object(11, 8, k, true, k != 2)};
    gt.num_objects = static_cast<int32_t>(gt.objects.size());
    log.WriteMessage(t, "GROUND_TRUTH", gt);
    if (!with_estimator) continue;

    slammtt_msgs::pose_t pose{};
    pose.utime = t;
    pose.x_m = k == 3 ? 0.3 : 0.0;
    pose.y_m = k;
    pose.heading_rad = M_PI / 2 + (k == 4 ? 0.1 : 0.0);
    log.WriteMessage(t, "POSE", pose);

    slammtt_msgs::tracks_t tracks{};
    tracks.utime = t;
    tracks.tracks.push_back(Track(k == 4 ? 102 : 100, 2.0 + k, 6.3, Trk::CLASS_MOVING));
    if (k != 3) tracks.tracks.push_back(Track(101, 8, k, Trk::CLASS_MOVING));
    tracks.tracks.push_back(
        Track(200, 5, 5, k == 0 ? Trk::CLASS_UNDECIDED : Trk::CLASS_STATIC));
    tracks.tracks.push_back(Track(300, 15, 15, Trk::CLASS_MOVING, false));
    if (k == 3) tracks.tracks.push_back(Track(400, 30, 30, Trk::CLASS_MOVING));
    tracks.num_tracks = static_cast<int32_t>(tracks.tracks.size());
    log.WriteMessage(t, "TRACKS", tracks);
  }
  if (with_estimator) {
    slammtt_msgs::map_t map{};
    map.utime = ScanTime(kScans - 1);
    const std::vector<std::pair<int64_t, Eigen::Vector2d>> landmarks = {
        {1001, Eigen::Vector2d(5.1, 5)},     // S1, 0.1 m off
        {1002, Eigen::Vector2d(10, -4.8)},   // S2, 0.2 m off
        {1003, Eigen::Vector2d(4, 6.5)},     // 0.5 m beside M1's path
        {1004, Eigen::Vector2d(50, 50)}};    // nothing
    for (const auto& [id, truth] : landmarks) {
      slammtt_msgs::landmark_t l{};
      l.id = id;
      const Eigen::Vector2d p = ToMap(truth.x(), truth.y());
      l.x_m = p.x();
      l.y_m = p.y();
      l.covariance[0] = 0.09;
      l.covariance[3] = 0.01;
      map.landmarks.push_back(l);
    }
    map.num_landmarks = static_cast<int32_t>(map.landmarks.size());
    log.WriteMessage(map.utime, "MAP", map);
    // A broken pose (NaN) is rejected and counted, never used.
    slammtt_msgs::pose_t bad{};
    bad.utime = ScanTime(kScans + 3);
    bad.x_m = std::numeric_limits<double>::quiet_NaN();
    log.WriteMessage(bad.utime, "POSE", bad);
  }
  log.Commit();
}

EvaluationReport EvaluateFile(const std::string& path, EvalInput* input) {
  LogReadResult read;
  *input = ReadEvalInput(path, Channels(), &read);
  EXPECT_TRUE(read.problem.empty()) << read.problem;
  return Evaluate(*input, EvalOptions());
}

TEST(EvaluationTest, HandBuiltLogGivesHandComputedFigures) {
  testing::TempDir dir;
  WriteHandBuiltLog(dir.File("run.lcm"), true);
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("run.lcm"), &input);
  EXPECT_EQ(input.rejected.at("pose"), 1);
  EXPECT_EQ(r.truth_scans, kScans);

  ASSERT_TRUE(r.robot.has_value());
  EXPECT_NEAR(r.robot->anchor.x_m, 2.0, 1e-12);
  EXPECT_NEAR(r.robot->anchor.y_m, 3.0, 1e-12);
  EXPECT_NEAR(r.robot->anchor.heading_rad, -M_PI / 2, 1e-12);
  EXPECT_NEAR(r.robot->error.rmse_m, std::sqrt(0.09 / 5), 1e-9);
  EXPECT_NEAR(r.robot->error.max_m, 0.3, 1e-9);
  EXPECT_NEAR(r.robot->error.final_heading_error_rad, 0.1, 1e-9);

  ASSERT_TRUE(r.odometry.has_value());
  EXPECT_NEAR(r.odometry->error.rmse_m, std::sqrt((0.04 + 0.16 + 0.36 + 0.64) / 5), 1e-9);
  EXPECT_NEAR(r.odometry->error.final_position_error_m, 0.8, 1e-9);

  ASSERT_TRUE(r.map.has_value());
  EXPECT_EQ(r.map->num_static_truth, 2);  // S3 was never visible
  EXPECT_EQ(r.map->num_matched, 2);
  EXPECT_DOUBLE_EQ(*r.map->static_recall, 1.0);
  EXPECT_NEAR(*r.map->landmark_rmse_m, std::sqrt((0.01 + 0.04) / 2), 1e-9);
  EXPECT_EQ(r.map->num_movers_in_static_map, 1);
  EXPECT_EQ(r.map->mover_landmarks, std::vector<int64_t>{1003});
  EXPECT_EQ(r.map->unexplained_landmarks, std::vector<int64_t>{1004});

  ASSERT_TRUE(r.tracking.has_value());
  const ClearMotSummary& c = r.tracking->clear_mot;
  EXPECT_EQ(c.num_truth, 9);
  EXPECT_EQ(c.num_matches, 8);
  EXPECT_EQ(c.num_misses, 1);
  EXPECT_EQ(c.num_false_positives, 1);
  EXPECT_EQ(c.num_id_switches, 1);
  EXPECT_EQ(c.num_fragmentations, 1);
  EXPECT_EQ(c.num_dont_care, 1);
  EXPECT_NEAR(*c.mota, 1.0 - 3.0 / 9.0, 1e-12);
  EXPECT_NEAR(*c.motp_m, 1.5 / 8.0, 1e-9);
  const double ospa_pair = std::sqrt(0.09 / 2);
  EXPECT_NEAR(r.tracking->ospa_mean_m,
              (3 * ospa_pair + 0.3 + std::sqrt((0.09 + 1.0) / 2)) / 5, 1e-9);
  EXPECT_NEAR(r.tracking->gospa_mean_m, (4 * 0.3 + std::sqrt(0.09 + 1.0)) / 5, 1e-9);
  ASSERT_EQ(r.tracking->scans.size(), 5u);
  EXPECT_NEAR(r.tracking->scans[2].ospa_m, 0.3, 1e-9);  // the don't-care track is left out
  EXPECT_EQ(r.tracking->scans[2].num_dont_care, 1);

  ASSERT_TRUE(r.classification.has_value());
  const ClassificationSummary& k = *r.classification;
  ASSERT_EQ(k.objects.size(), 4u);  // S1, S2, M1, M2 (S3 never visible)
  EXPECT_DOUBLE_EQ(*k.accuracy, 0.75);  // S2 was never tracked
  EXPECT_DOUBLE_EQ(*k.accuracy_of_tracked, 1.0);
  EXPECT_NEAR(*k.objects[0].delay_s, 0.125, 1e-12);  // S1: undecided in its first scan
  EXPECT_EQ(k.confusion[0][kUntrackedColumn], 1);
  EXPECT_EQ(k.confusion[1][1], 2);

  EXPECT_EQ(r.track_paths.size(), 4u);  // 100, 101, 102, 400
  ASSERT_EQ(r.landmarks.size(), 4u);
  EXPECT_NEAR(r.landmarks[0].position_m.x(), 5.1, 1e-12);
  EXPECT_NEAR(r.landmarks[0].covariance(1, 1), 0.09, 1e-12);  // rotated by -90 degrees

  // The JSON carries exactly the agreed top-level keys plus the detail.
  const nlohmann::json j = ReportToJson(input, r);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() != "detail") keys.push_back(it.key());
  }
  std::vector<std::string> expected = TopLevelMetricKeys();
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(j.size(), expected.size() + 1);
  EXPECT_NEAR(j["ate_rmse_m"].get<double>(), std::sqrt(0.09 / 5), 1e-9);
  EXPECT_EQ(j["id_switches"], 1);
  EXPECT_EQ(j["fragmentations"], 1);
  EXPECT_EQ(j["movers_in_static_map"], 1);
  EXPECT_DOUBLE_EQ(j["static_recall"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["classification_accuracy"].get<double>(), 0.75);
  EXPECT_EQ(j["detail"]["classification"]["confusion_true_by_final"]["static"]["untracked"], 1);
}

TEST(EvaluationTest, AWorldOnlyLogScoresOdometryAndSaysWhatIsMissing) {
  testing::TempDir dir;
  WriteHandBuiltLog(dir.File("world.lcm"), false);
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("world.lcm"), &input);
  EXPECT_TRUE(r.odometry.has_value());
  EXPECT_FALSE(r.robot.has_value());
  EXPECT_FALSE(r.tracking.has_value());
  const nlohmann::json j = ReportToJson(input, r);
  for (const std::string& key : TopLevelMetricKeys()) {
    if (key == "odometry_ate_rmse_m") {
      EXPECT_TRUE(j[key].is_number());
    } else {
      EXPECT_TRUE(j[key].is_null()) << key;
    }
  }
  ASSERT_EQ(j["detail"]["notes"].size(), 1u);
  EXPECT_NE(j["detail"]["notes"][0].get<std::string>().find("no POSE"), std::string::npos);
  // The pictures are still drawn, with the missing parts said so.
  EXPECT_NE(MapSvg(r).find("no MAP in the log"), std::string::npos);
}

TEST(EvaluationTest, NoGroundTruthScoresNothing) {
  EvalInput input;
  input.odometry.push_back({0, Pose2{}});
  const EvaluationReport r = Evaluate(input, EvalOptions());
  EXPECT_FALSE(r.odometry.has_value());
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.back().find("no GROUND_TRUTH"), std::string::npos);
  EXPECT_TRUE(ReportToJson(input, r)["ate_rmse_m"].is_null());
  EXPECT_THROW(Evaluate(input, EvalOptions{0.0, 1.0, 2.0, 2.0}), std::invalid_argument);
}

std::string RunCommand(const std::string& command, int* status) {
  std::FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.append(buffer, n);
  *status = pclose(pipe);
  return out;
}

TEST(EvalProgramTest, WritesJsonSummaryAndPictures) {
  testing::TempDir dir;
  WriteHandBuiltLog(dir.File("run.lcm"), true);
  int status = 0;
  const std::string out = RunCommand(std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval " +
                                         dir.File("run.lcm") + " --json " +
                                         dir.File("report.json") + " --plots " +
                                         dir.File("plots") + " 2>&1",
                                     &status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("identity switches"), std::string::npos) << out;
  EXPECT_NE(out.find("pictures: " + dir.File("plots")), std::string::npos) << out;
  const nlohmann::json j = nlohmann::json::parse(testing::FileBytes(dir.File("report.json")));
  EXPECT_EQ(j["id_switches"], 1);
  EXPECT_NEAR(j["mota"].get<double>(), 2.0 / 3.0, 1e-12);
  for (const char* name : {"trajectory.svg", "map.svg", "tracks.svg", "errors.svg"}) {
    const std::string svg = testing::FileBytes(dir.File("plots") + "/" + name);
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u) << name;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << name;
    EXPECT_EQ(svg.find("nan"), std::string::npos) << name;
    EXPECT_LT(svg.size(), 200000u) << name;
  }
  // Same log, same report: byte for byte.
  RunCommand(std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval " + dir.File("run.lcm") + " --json " +
                 dir.File("again.json") + " >/dev/null 2>&1",
             &status);
  EXPECT_EQ(testing::FileBytes(dir.File("again.json")),
            testing::FileBytes(dir.File("report.json")));
}

TEST(EvalProgramTest, ACorruptLogWritesNoReport) {
  testing::TempDir dir;
  WriteHandBuiltLog(dir.File("run.lcm"), true);
  std::string bytes = testing::FileBytes(dir.File("run.lcm"));
  // Break the second event's sync word.
  const size_t second = bytes.find("\xED\xA1\xDA\x01", 4);
  ASSERT_NE(second, std::string::npos);
  bytes[second] = 0;
  testing::WriteFileBytes(dir.File("bad.lcm"), bytes);
  int status = 0;
  const std::string out = RunCommand(std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval " +
                                         dir.File("bad.lcm") + " --json " +
                                         dir.File("report.json") + " 2>&1",
                                     &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("corrupt event header"), std::string::npos) << out;
  EXPECT_FALSE(testing::FileExists(dir.File("report.json")));
}

}  // namespace
}  // namespace slammtt
