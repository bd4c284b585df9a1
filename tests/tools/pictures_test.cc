// The pictures of slammtt-eval (tools/plots): legends outside the data, OSPA/GOSPA gaps where
// nothing is there to track, the identity timeline's markers against the report's counts,
// landmark ids that do not overlap, and the pictures of a log without ground truth.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "tests/tools/hand_built_log.h"
#include "tests/tools/log_test_util.h"
#include "tests/tools/svg_geometry.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/plots/eval_plots.h"
#include "tools/plots/label_placement.h"
#include "tools/plots/svg_plot.h"

namespace slammtt {
namespace {

using testing::DataBoxes;
using testing::ElementsOfRole;
using testing::LegendBoxes;
using testing::PixelBox;

constexpr int64_t kT0 = 5000000;
constexpr int64_t kScanUs = 125000;
constexpr int kScans = 40;
int64_t At(int k) { return kT0 + k * kScanUs; }

// Pose on a 20 x 20 m square loop at scan k (40 scans once around).
Pose2 Loop(int k) {
  const double s = 80.0 * k / kScans;  // metres along the loop
  if (s < 20) return {s, 0, 0};
  if (s < 40) return {20, s - 20, M_PI / 2};
  if (s < 60) return {60 - s, 20, M_PI};
  return {0, 80 - s, -M_PI / 2};
}

// A run whose data fill the frame: the robot drives a square loop (POSE and ODOMETRY equal to
// the truth), 81 posts on a 2.5 m grid over the whole square, each mapped by a landmark (id
// 1000 + k); one mover walks the diagonal from (0, 20) to (20, 0), out of view in scans 15-24
// with no track either (nothing to track), tracked by 7 in scans 0-14, by 8 from scan 25 (one
// identity switch) except scans 30-31 (a miss, then a fragmentation at scan 32).
EvalInput FullFrameRun() {
  EvalInput input;
  input.source = "full-frame";
  for (int k = 0; k < kScans; ++k) {
    TruthScan scan;
    scan.utime = At(k);
    scan.robot = Loop(k);
    int64_t id = 1;
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) {
        scan.objects.push_back({id++, Eigen::Vector2d(2.5 * i, 2.5 * j), Eigen::Vector2d::Zero(),
                                false, true, 5, TruthKind::kPost});
      }
    }
    const Eigen::Vector2d mover(20.0 * k / kScans, 20.0 - 20.0 * k / kScans);
    const bool in_view = k < 15 || k > 24;
    scan.objects.push_back({500, mover, Eigen::Vector2d(4, -4), true, in_view, 5,
                            TruthKind::kPerson});
    input.truth.push_back(scan);
    input.estimate.push_back({At(k), scan.robot});
    input.odometry.push_back({At(k), scan.robot});
    TrackScan tracks;
    tracks.utime = At(k);
    if (k < 15) tracks.tracks.push_back({7, mover, ObjectLabel::kMoving, true, true, true});
    if (k > 24 && k != 30 && k != 31) {
      tracks.tracks.push_back(
          {8, mover + Eigen::Vector2d(0.1, 0), ObjectLabel::kMoving, true, true, true});
    }
    input.tracks.push_back(tracks);
  }
  std::vector<LandmarkSample> map;
  for (size_t k = 0; k < 81; ++k) {
    const Eigen::Vector2d p = input.truth.back().objects[k].position_m;
    map.push_back({static_cast<int64_t>(1000 + k), p + Eigen::Vector2d(0.05, 0.0),
                   Eigen::Matrix2d::Identity() * 0.01});
  }
  input.final_map = map;
  input.final_map_utime = At(kScans - 1);
  return input;
}

// The report of the hand-built log of eval_test.cc (1 identity switch, 1 fragmentation).
EvaluationReport HandBuiltReport() {
  testing::TempDir dir;
  testing::WriteHandBuiltLog(dir.File("run.lcm"), true);
  LogReadResult read;
  return Evaluate(ReadEvalInput(dir.File("run.lcm"), Channels(), &read), EvalOptions());
}

void ExpectNoLegendOnData(const std::string& name, const std::string& svg) {
  const std::vector<PixelBox> legends = LegendBoxes(svg);
  const std::vector<PixelBox> data = DataBoxes(svg);
  EXPECT_FALSE(data.empty()) << name;
  for (const PixelBox& legend : legends) {
    for (const PixelBox& d : data) {
      EXPECT_FALSE(legend.Intersects(d))
          << name << ": legend (" << legend.left << ", " << legend.top << ", " << legend.right
          << ", " << legend.bottom << ") covers data (" << d.left << ", " << d.top << ", "
          << d.right << ", " << d.bottom << ")";
    }
  }
}

TEST(PicturesTest, NoLegendCoversDataInAnyPicture) {
  const EvaluationReport full = Evaluate(FullFrameRun(), EvalOptions());
  const EvaluationReport hand = HandBuiltReport();
  for (const EvaluationReport* report : {&full, &hand}) {
    int legends = 0;
    for (const auto& [name, svg] : EvaluationPlots(*report)) {
      if (name == "scan.svg") continue;  // no scan in these logs: an empty panel, no legend
      legends += static_cast<int>(LegendBoxes(svg).size());
      ExpectNoLegendOnData(report->source + "/" + name, svg);
    }
    EXPECT_EQ(legends, 6) << report->source;  // one per picture, two in errors.svg
  }
  // The data of the full-frame run reach every edge of the map panel: the check has teeth there.
  const std::vector<PixelBox> map_data = DataBoxes(MapSvg(full));
  const std::vector<PixelBox> legend = LegendBoxes(MapSvg(full));
  ASSERT_EQ(legend.size(), 1u);
  double lowest = 0;
  for (const PixelBox& b : map_data) lowest = std::max(lowest, b.bottom);
  EXPECT_GT(lowest, legend[0].top - 80);
}

// The README's pictures (docs/images, scripts/make-readme-pictures.sh): real runs, the office
// scan among them.
TEST(PicturesTest, NoLegendCoversDataInTheReadmePictures) {
  for (const char* name : {"s1-crossing-trajectory.svg", "s1-crossing-map.svg",
                           "s1-crossing-tracks.svg", "s1-crossing-identities.svg",
                           "s1-crossing-errors.svg", "office-scan.svg"}) {
    const std::string svg =
        testing::FileBytes(std::string(SLAMMTT_SOURCE_DIR) + "/docs/images/" + name);
    EXPECT_FALSE(LegendBoxes(svg).empty()) << name;
    ExpectNoLegendOnData(name, svg);
  }
}

TEST(PicturesTest, OspaAndGospaHaveGapsWhereNothingIsThereToTrack) {
  const EvaluationReport r = Evaluate(FullFrameRun(), EvalOptions());
  ASSERT_TRUE(r.tracking.has_value());
  ASSERT_EQ(r.tracking->scans.size(), static_cast<size_t>(kScans));
  int nothing = 0;
  for (const TrackingScan& s : r.tracking->scans) nothing += NothingToTrack(s) ? 1 : 0;
  EXPECT_EQ(nothing, 10);  // scans 15-24
  EXPECT_DOUBLE_EQ(r.tracking->scans[20].ospa_m, 0.0);  // the definition's value stays
  const std::string svg = ErrorsSvg(r);
  for (const char* role : {"ospa", "gospa"}) {
    const std::vector<std::string> lines = ElementsOfRole(svg, role);
    ASSERT_EQ(lines.size(), 1u) << role;  // one path, no lone points
    const std::string d = testing::TextAttribute(lines[0], "d");
    // Two runs (scans 0-14 and 25-39), one vertex per scan, none in the gap.
    EXPECT_EQ(std::count(d.begin(), d.end(), 'M'), 2) << d;
    EXPECT_EQ(std::count(d.begin(), d.end(), 'M') + std::count(d.begin(), d.end(), 'L'), 30);
  }
  // A gap of one scan between two runs is a gap too, and a lone scored scan a dot.
  EvaluationReport lone = r;
  for (int k : {5, 7}) {
    lone.tracking->scans[k].num_truth = 0;
    lone.tracking->scans[k].num_tracks = 0;
  }
  const std::string lone_svg = ErrorsSvg(lone);
  const std::string d = testing::TextAttribute(ElementsOfRole(lone_svg, "ospa")[0], "d");
  EXPECT_EQ(std::count(d.begin(), d.end(), 'M'), 3) << d;  // 0-4, 8-14, 25-39
  EXPECT_EQ(ElementsOfRole(lone_svg, "ospa").size(), 2u);  // the path and the dot of scan 6
}

int CountRole(const std::string& svg, const std::string& role) {
  return static_cast<int>(ElementsOfRole(svg, role).size());
}

TEST(PicturesTest, TimelineMarksEveryIdentitySwitchAndFragmentationTheReportCounts) {
  const EvaluationReport full = Evaluate(FullFrameRun(), EvalOptions());
  ASSERT_TRUE(full.tracking.has_value());
  EXPECT_EQ(full.tracking->clear_mot.num_id_switches, 1);
  EXPECT_EQ(full.tracking->clear_mot.num_fragmentations, 1);
  const EvaluationReport hand = HandBuiltReport();
  for (const EvaluationReport* r : {&full, &hand}) {
    const std::string svg = IdentityTimelineSvg(*r);
    EXPECT_EQ(CountRole(svg, "id-switch"), r->tracking->clear_mot.num_id_switches) << r->source;
    EXPECT_EQ(CountRole(svg, "fragmentation"), r->tracking->clear_mot.num_fragmentations)
        << r->source;
  }
  // The full-frame mover: tracked by 7 (scans 0-14), by 8 (25-29, 32-39), missed at 30-31.
  const std::string svg = IdentityTimelineSvg(full);
  const std::vector<std::string> tracked = ElementsOfRole(svg, "tracked");
  ASSERT_EQ(tracked.size(), 3u);
  EXPECT_NE(tracked[0].find(IdentityColour(7)), std::string::npos);
  EXPECT_NE(tracked[1].find(IdentityColour(8)), std::string::npos);
  EXPECT_EQ(CountRole(svg, "miss"), 1);
  EXPECT_NE(svg.find(">500</text>"), std::string::npos);  // the row's label: the mover's id
}

TEST(PicturesTest, LandmarkIdsAreWrittenWithoutOverlapping) {
  const std::string svg = MapSvg(Evaluate(FullFrameRun(), EvalOptions()));
  std::vector<PixelBox> labels;
  for (const std::string& line : testing::SvgLines(svg)) {
    const size_t close = line.find("</text>");
    if (line.rfind("<text", 0) != 0 || close == std::string::npos) continue;
    const std::string text = line.substr(line.find('>') + 1, close - line.find('>') - 1);
    if (text.size() == 4 && text[0] == '1' && text >= "1000" && text <= "1080") {
      labels.push_back(testing::ElementBox(line));
    }
  }
  ASSERT_EQ(labels.size(), 81u);
  for (size_t a = 0; a < labels.size(); ++a) {
    for (size_t b = a + 1; b < labels.size(); ++b) {
      EXPECT_FALSE(labels[a].Intersects(labels[b])) << a << " " << b;
    }
  }
}

TEST(LabelPlacementTest, MovesALabelAsideWhenItsFirstPlaceIsTaken) {
  // Two points 10 px apart: the second label's first place (right-above) would cover the first's
  // neighbourhood... each label goes where it overlaps nothing.
  const std::vector<Eigen::Vector2d> points = {{100, 100}, {110, 100}, {105, 110}};
  const std::vector<PlacedLabel> placed = PlaceLabels(points, {"1234", "1235", "1236"}, 9, 2.5);
  ASSERT_EQ(placed.size(), 3u);
  EXPECT_EQ(CountLabelOverlaps(placed), 0);
  // Always one label per point, also where overlaps cannot be avoided.
  const std::vector<Eigen::Vector2d> same(12, Eigen::Vector2d(50, 50));
  EXPECT_EQ(PlaceLabels(same, std::vector<std::string>(12, "7"), 9, 2.5).size(), 12u);
  EXPECT_THROW(PlaceLabels(same, {"1"}, 9, 2.5), std::invalid_argument);
}

// The hand-built log without its GROUND_TRUTH: a robot log.
std::string WriteLogWithoutTruth(const testing::TempDir& dir) {
  testing::WriteHandBuiltLog(dir.File("with-truth.lcm"), true);
  std::vector<LogEvent> events;
  for (LogEvent& e : testing::ReadLog(dir.File("with-truth.lcm"))) {
    if (e.channel != "GROUND_TRUTH") events.push_back(std::move(e));
  }
  testing::WriteLog(dir.File("robot.lcm"), events);
  return dir.File("robot.lcm");
}

TEST(PicturesTest, ALogWithoutGroundTruthIsDrawnFromTheLogAlone) {
  testing::TempDir dir;
  LogReadResult read;
  const EvalInput input = ReadEvalInput(WriteLogWithoutTruth(dir), Channels(), &read);
  const EvaluationReport r = Evaluate(input, EvalOptions());
  EXPECT_FALSE(r.robot || r.odometry || r.map || r.tracking || r.classification);
  ASSERT_TRUE(r.log_only.has_value());
  EXPECT_EQ(r.log_only->estimate.size(), 5u);  // the NaN pose is rejected
  ASSERT_EQ(r.log_only->odometry.size(), 6u);
  // The odometry is anchored to the estimate at the first POSE (interpolated there).
  EXPECT_TRUE(r.log_only->odometry_anchored_to_estimate);
  const auto at_first = InterpolatePose(r.log_only->odometry, testing::ScanTime(0));
  ASSERT_TRUE(at_first.has_value());
  EXPECT_NEAR(at_first->x_m, 0.0, 1e-9);
  EXPECT_NEAR(at_first->y_m, 0.0, 1e-9);
  EXPECT_NEAR(at_first->heading_rad, M_PI / 2, 1e-9);
  ASSERT_EQ(r.landmarks.size(), 4u);
  std::set<int64_t> track_ids;
  for (const TrackPath& t : r.track_paths) track_ids.insert(t.id);
  EXPECT_EQ(track_ids, (std::set<int64_t>{100, 101, 102, 400}));  // 300 is unconfirmed
  EXPECT_EQ(r.first_utime, testing::ScanTime(0) - testing::kScanUs / 2);  // the first odometry
  const std::string trajectory = TrajectorySvg(r);
  EXPECT_NE(trajectory.find("estimate (POSE)"), std::string::npos);
  EXPECT_NE(trajectory.find("odometry (anchored to the estimate"), std::string::npos);
  EXPECT_NE(trajectory.find("no ground truth"), std::string::npos);
  const std::string map = MapSvg(r);
  for (int id : {1001, 1002, 1003, 1004}) {
    EXPECT_NE(map.find(">" + std::to_string(id) + "</text>"), std::string::npos) << id;
  }
  EXPECT_EQ(map.find("no MAP"), std::string::npos);
  const std::string tracks = TracksSvg(r);
  for (int64_t id : track_ids) {
    EXPECT_NE(tracks.find(">" + std::to_string(id) + "</text>"), std::string::npos) << id;
  }
  EXPECT_NE(ErrorsSvg(r).find("no ground truth in the log"), std::string::npos);
  EXPECT_NE(IdentityTimelineSvg(r).find("no ground truth in the log"), std::string::npos);
}

TEST(PicturesTest, EvalOnARobotLogWritesNoReportExitsOneAndStillDraws) {
  testing::TempDir dir;
  const std::string log = WriteLogWithoutTruth(dir);
  const std::string program = std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval " + log;
  int status = 0;
  std::string out = testing::RunCommand(program + " --json " + dir.File("r.json") + " --plots " +
                                            dir.File("pictures") + " 2>&1",
                                        &status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status << out;
  EXPECT_NE(out.find(log + ": no GROUND_TRUTH: nothing can be scored; no report written"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("pictures of what the log holds, nothing scored: " + dir.File("pictures")),
            std::string::npos)
      << out;
  EXPECT_FALSE(testing::FileExists(dir.File("r.json")));
  for (const char* name : {"trajectory.svg", "map.svg", "tracks.svg", "identities.svg",
                           "errors.svg", "scan.svg"}) {
    EXPECT_TRUE(testing::FileExists(dir.File("pictures") + "/" + name)) << name;
  }
  EXPECT_NE(testing::FileBytes(dir.File("pictures") + "/map.svg").find(">1003</text>"),
            std::string::npos);
  // Without --plots: the same status and line, nothing written.
  out = testing::RunCommand(program + " --json " + dir.File("r.json") + " 2>&1", &status);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status << out;
  EXPECT_EQ(out.find("pictures"), std::string::npos) << out;
  EXPECT_FALSE(testing::FileExists(dir.File("r.json")));
}

}  // namespace
}  // namespace slammtt
