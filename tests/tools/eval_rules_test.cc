// The evaluation's rules for what an estimator can know (docs/evaluation.md): visibility by
// beams in a log with LASER_SCAN, movers standing still, and the listed identity switches. Each
// log is built here scan by scan; every figure is computed by hand in the comments.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "runtime/config.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "tests/tools/hand_built_log.h"
#include "tests/tools/log_test_util.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/eval/report_json.h"
#include "tools/plots/eval_plots.h"

namespace slammtt {
namespace {

using testing::RunCommand;

using Obj = slammtt_msgs::object_truth_t;
using Trk = slammtt_msgs::track_t;
constexpr int64_t kT0 = 2000000;
constexpr int64_t kScanUs = 125000;

int64_t At(int k) { return kT0 + k * kScanUs; }

Obj Truth(int64_t id, double x, double y, bool moving, double vx_mps, int beams, bool visible) {
  Obj o{};
  o.id = id;
  o.x_m = x;
  o.y_m = y;
  o.vx_mps = vx_mps;
  o.radius_m = 0.25;
  o.object_class = moving ? Obj::CLASS_MOVING : Obj::CLASS_STATIC;
  o.beams_on_object = beams;
  o.visible = visible;
  return o;
}

Trk Track(int64_t id, double x, double y, int8_t cls) {
  Trk t{};
  t.id = id;
  t.x_m = x;
  t.y_m = y;
  t.covariance[0] = t.covariance[5] = 0.04;
  t.object_class = cls;
  t.confirmed = true;
  t.reported = true;
  t.measured = true;
  t.hits = 3;
  return t;
}

// Writes one scan: the ground truth, a POSE at the truth pose (the robot stands at the origin,
// so the map frame is the truth frame), the tracks and, in a scan log, an (empty) LASER_SCAN.
void WriteScan(LogWriter* log, int k, const std::vector<Obj>& objects,
               const std::vector<Trk>& tracks, bool scan_log) {
  const int64_t t = At(k);
  if (scan_log) {
    slammtt_msgs::laser_scan_t scan{};
    scan.utime = t;
    scan.sequence = k;
    scan.range_max_m = 30.0f;
    log->WriteMessage(t, "LASER_SCAN", scan);
  }
  slammtt_msgs::ground_truth_t gt{};
  gt.utime = t;
  gt.objects = objects;
  gt.num_objects = static_cast<int32_t>(objects.size());
  log->WriteMessage(t, "GROUND_TRUTH", gt);
  slammtt_msgs::pose_t pose{};
  pose.utime = t;
  log->WriteMessage(t, "POSE", pose);
  slammtt_msgs::tracks_t msg{};
  msg.utime = t;
  msg.tracks = tracks;
  msg.num_tracks = static_cast<int32_t>(tracks.size());
  log->WriteMessage(t, "TRACKS", msg);
}

// Four scans. Mover 10 walks (1 m/s) hit by 2 beams only; the world calls it visible (>= 1
// beam, or a point feature in a feature log). Mover 11 walks hit by 5 beams, tracked by 110
// throughout. Track 100 follows mover 10 from scan 2. Static post 1 is hit by 2 beams. The final
// MAP is empty.
void WriteTwoBeamLog(const std::string& path, bool scan_log) {
  LogWriter log(path);
  for (int k = 0; k < 4; ++k) {
    std::vector<Trk> tracks = {Track(110, 5.0 + 0.125 * k, 2, Trk::CLASS_MOVING)};
    if (k >= 2) tracks.push_back(Track(100, 15.0 + 0.125 * k, 0.2, Trk::CLASS_MOVING));
    WriteScan(&log, k,
              {Truth(1, 20, 5, false, 0.0, 2, true),
               Truth(10, 15.0 + 0.125 * k, 0, true, 1.0, 2, true),
               Truth(11, 5.0 + 0.125 * k, 2, true, 1.0, 5, true)},
              tracks, scan_log);
  }
  slammtt_msgs::map_t map{};
  map.utime = At(3);
  log.WriteMessage(map.utime, "MAP", map);
  log.Commit();
}

EvaluationReport EvaluateFile(const std::string& path, const EvalOptions& options,
                              EvalInput* input) {
  LogReadResult read;
  *input = ReadEvalInput(path, Channels(), &read);
  EXPECT_TRUE(read.problem.empty()) << read.problem;
  return Evaluate(*input, options);
}

TEST(EvalPeopleTest, MoversThatAreNoPersonAreCountedByIdentity) {
  // The two-beam scan log (movers 10, invisible, and 11, tracked by 110 throughout) plus: track
  // 200, MOVING at every scan 10 m from anything (the scenery taken for a mover); 201, MOVING on
  // the invisible mover 10 (excused); 202, STATIC far away (no mover). One identity over the
  // TRACKS span of 3 scans of 0.125 s: 1 / (0.375 s / 60) = 160 per minute.
  testing::TempDir dir;
  {
    LogWriter log(dir.File("scans.lcm"));
    for (int k = 0; k < 4; ++k) {
      WriteScan(&log, k,
                {Truth(10, 15.0 + 0.125 * k, 0, true, 1.0, 2, true),
                 Truth(11, 5.0 + 0.125 * k, 2, true, 1.0, 5, true)},
                {Track(110, 5.0 + 0.125 * k, 2, Trk::CLASS_MOVING),
                 Track(200, 25.0, 10.0, Trk::CLASS_MOVING),
                 Track(201, 15.0 + 0.125 * k, 0.1, Trk::CLASS_MOVING),
                 Track(202, 40.0, 0.0, Trk::CLASS_STATIC)},
                true);
    }
    log.Commit();
  }
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("scans.lcm"), EvalOptions(), &input);
  ASSERT_TRUE(r.people_tracking.has_value());
  EXPECT_EQ(r.people_tracking->false_mover_identities, 1);
  EXPECT_NEAR(r.people_tracking->false_movers_per_minute, 160.0, 1e-9);
  const nlohmann::json j = ReportToJson(input, r);
  EXPECT_NEAR(j["non_person_movers_per_minute"].get<double>(), 160.0, 1e-9);
  EXPECT_EQ(j["detail"]["people_tracking"]["false_mover_identities"], 1);
  EXPECT_EQ(j["detail"]["people_tracking"]["false_mover_ids"], nlohmann::json::array({200}));
}

TEST(EvalVisibilityTest, TwoBeamsAreSeenInAFeatureLog) {
  // Feature log: the world's flag. Truth sets {10, 11} x 4 scans = 8; 11 matched 4 times, 10 at
  // scans 2-3: 2 misses, MOTA = 1 - 2/8. The post counts for the map (recall 0 of 1) and the
  // classification: 10 and 11 right (moving), 1 untracked: 2/3.
  testing::TempDir dir;
  WriteTwoBeamLog(dir.File("features.lcm"), false);
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("features.lcm"), EvalOptions(), &input);
  EXPECT_EQ(input.laser_scans, 0);
  EXPECT_FALSE(r.scan_log);
  ASSERT_TRUE(r.tracking.has_value());
  const ClearMotSummary& c = r.tracking->clear_mot;
  EXPECT_EQ(c.num_truth, 8);
  EXPECT_EQ(c.num_matches, 6);
  EXPECT_EQ(c.num_misses, 2);
  EXPECT_EQ(c.num_false_positives, 0);
  EXPECT_DOUBLE_EQ(*c.mota, 0.75);
  EXPECT_EQ(r.tracking->mover_scans_few_beams, 0);
  ASSERT_TRUE(r.map.has_value());
  EXPECT_EQ(r.map->num_static_truth, 1);
  EXPECT_DOUBLE_EQ(*r.map->static_recall, 0.0);
  ASSERT_TRUE(r.classification.has_value());
  EXPECT_EQ(r.classification->objects.size(), 3u);
  EXPECT_DOUBLE_EQ(*r.classification->accuracy, 2.0 / 3.0);
}

TEST(EvalVisibilityTest, TwoBeamsAreNotVisibleInAScanLog) {
  // The same truth with LASER_SCAN in the log: 2 beams < min_beams (3), so mover 10 is not
  // visible: truth = {11} x 4, all matched, MOTA 1; track 100 coasts on an invisible mover: don't
  // care at scans 2 and 3. The post never was visible: no static truth (recall null), and the
  // classification scores 11 alone.
  testing::TempDir dir;
  WriteTwoBeamLog(dir.File("scans.lcm"), true);
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("scans.lcm"), EvalOptions(), &input);
  EXPECT_EQ(input.laser_scans, 4);
  EXPECT_TRUE(r.scan_log);
  ASSERT_TRUE(r.tracking.has_value());
  const TrackingResult& t = *r.tracking;
  EXPECT_EQ(t.clear_mot.num_truth, 4);
  EXPECT_EQ(t.clear_mot.num_matches, 4);
  EXPECT_EQ(t.clear_mot.num_misses, 0);
  EXPECT_EQ(t.clear_mot.num_false_positives, 0);
  EXPECT_EQ(t.clear_mot.num_dont_care, 2);
  EXPECT_EQ(t.clear_mot.num_dont_care_positions, 2);
  EXPECT_DOUBLE_EQ(*t.clear_mot.mota, 1.0);
  EXPECT_EQ(t.mover_scans_few_beams, 4);
  EXPECT_EQ(t.mover_scans_invisible, 4);
  EXPECT_EQ(t.movers_few_beams, 1);
  ASSERT_EQ(t.scans.size(), 4u);
  EXPECT_EQ(t.scans[0].num_few_beams, 1);
  EXPECT_DOUBLE_EQ(t.ospa_mean_m, 0.0);  // the don't-care track is out of the OSPA set too
  ASSERT_TRUE(r.map.has_value());
  EXPECT_EQ(r.map->num_static_truth, 0);
  EXPECT_FALSE(r.map->static_recall.has_value());
  EXPECT_EQ(r.statics_few_beams_only, 1);
  EXPECT_EQ(r.movers_few_beams_only, 1);
  ASSERT_TRUE(r.classification.has_value());
  ASSERT_EQ(r.classification->objects.size(), 1u);
  EXPECT_EQ(r.classification->objects[0].id, 11);

  const nlohmann::json j = ReportToJson(input, r);
  EXPECT_EQ(j["detail"]["input"]["laser_scans"], 4);
  EXPECT_EQ(j["detail"]["options"]["min_beams"], 3);
  EXPECT_EQ(j["detail"]["tracking"]["dont_care"]["mover_scans_few_beams"], 4);
  EXPECT_EQ(j["detail"]["tracking"]["dont_care"]["tracks_near_invisible_movers"], 2);
  EXPECT_EQ(j["detail"]["map"]["static_objects_few_beams_only"], 1);
  EXPECT_EQ(j["detail"]["classification"]["movers_few_beams_only"], 1);
  EXPECT_EQ(j["detail"]["tracking"]["per_scan"]["few_beams"],
            nlohmann::json::array({1, 1, 1, 1}));

  // min_beams 2 sees what two beams hit: the feature log's figures again.
  EvalOptions two;
  two.min_beams = 2;
  const EvaluationReport r2 = Evaluate(input, two);
  EXPECT_EQ(r2.tracking->clear_mot.num_truth, 8);
  EXPECT_DOUBLE_EQ(*r2.tracking->clear_mot.mota, 0.75);
  EXPECT_EQ(r2.map->num_static_truth, 1);
}

// A person on two legs (KIND_PERSON 20 with legs 21 and 22) walks at 1 m/s, tracked by 120 at
// every scan. Its legs are hit by 2 + 2 beams at scans 0-1 (4 beams on the person, but no leg
// has the 3 a cluster needs: not visible) and by 1 + 4 beams at scans 2-3 (visible). So the
// truth set is {20} at scans 2-3: 2 matches, and the track at scans 0-1 coasts on an existing
// but invisible person: don't care. The legs are never objects of their own.
Obj Leg(int64_t id, int64_t person, double x, double y, int beams) {
  Obj o = Truth(id, x, y, true, 1.0, beams, beams > 0);
  o.radius_m = 0.06;
  o.kind = Obj::KIND_LEG;
  o.parent_id = person;
  return o;
}

Obj Person(int64_t id, double x, double y, int beams) {
  Obj o = Truth(id, x, y, true, 1.0, beams, beams > 0);
  o.kind = Obj::KIND_PERSON;
  o.parent_id = -1;
  return o;
}

TEST(EvalPeopleTest, APersonIsVisibleWhenOneLegHasTheBeamsOfACluster) {
  testing::TempDir dir;
  LogWriter log(dir.File("legs.lcm"));
  for (int k = 0; k < 4; ++k) {
    const double x = 5.0 + 0.125 * k;
    const int a = k < 2 ? 2 : 1;
    const int b = k < 2 ? 2 : 4;
    WriteScan(&log, k,
              {Person(20, x, 1, a + b), Leg(21, 20, x, 1.1, a), Leg(22, 20, x, 0.9, b)},
              {Track(120, x, 1, Trk::CLASS_MOVING)}, true);
  }
  log.Commit();
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("legs.lcm"), EvalOptions(), &input);
  ASSERT_EQ(input.truth.size(), 4u);
  for (const TruthScan& scan : input.truth) {
    ASSERT_EQ(scan.objects.size(), 1u);  // the legs are folded into the person
    EXPECT_EQ(scan.objects[0].id, 20);
    EXPECT_EQ(scan.objects[0].kind, TruthKind::kPerson);
  }
  EXPECT_EQ(input.truth[0].objects[0].beams_on_object, 2);  // the better leg, not the sum
  EXPECT_EQ(input.truth[3].objects[0].beams_on_object, 4);
  ASSERT_TRUE(r.tracking.has_value());
  const ClearMotSummary& c = r.tracking->clear_mot;
  EXPECT_EQ(c.num_truth, 2);
  EXPECT_EQ(c.num_matches, 2);
  EXPECT_EQ(c.num_false_positives, 0);
  EXPECT_EQ(c.num_dont_care, 2);
  EXPECT_DOUBLE_EQ(*c.mota, 1.0);
}

TEST(EvalPeopleTest, ALegWithoutItsPersonRejectsTheScan) {
  testing::TempDir dir;
  LogWriter log(dir.File("orphan.lcm"));
  WriteScan(&log, 0, {Person(20, 5, 1, 6), Leg(21, 20, 5, 1.1, 3), Leg(22, 20, 5, 0.9, 3)}, {},
            true);
  WriteScan(&log, 1, {Person(20, 5, 1, 3), Leg(21, 99, 5, 1.1, 3)}, {}, true);
  log.Commit();
  LogReadResult read;
  const EvalInput input = ReadEvalInput(dir.File("orphan.lcm"), Channels(), &read);
  EXPECT_EQ(input.truth.size(), 1u);
  EXPECT_EQ(input.rejected.at("ground_truth"), 1);
}

TEST(EvalPeopleTest, WallsAreReadDrawnAndNeverPartOfThePointMap) {
  testing::TempDir dir;
  LogWriter log(dir.File("walls.lcm"));
  for (int k = 0; k < 2; ++k) {
    slammtt_msgs::ground_truth_t gt{};
    gt.utime = At(k);
    gt.objects = {Truth(1, 3, 3, false, 0.0, 5, true)};
    gt.objects[0].kind = Obj::KIND_POST;
    gt.num_objects = 1;
    slammtt_msgs::segment_truth_t wall{};
    wall.id = 7;
    wall.kind = slammtt_msgs::segment_truth_t::KIND_WALL;
    wall.x0_m = -2.0;
    wall.y0_m = 4.0;
    wall.x1_m = 6.0;
    wall.y1_m = 4.0;
    wall.beams_on_segment = 40;
    gt.segments = {wall};
    gt.num_segments = 1;
    log.WriteMessage(gt.utime, "GROUND_TRUTH", gt);
    slammtt_msgs::pose_t pose{};
    pose.utime = At(k);
    log.WriteMessage(pose.utime, "POSE", pose);
  }
  slammtt_msgs::map_t map{};
  map.utime = At(1);
  log.WriteMessage(map.utime, "MAP", map);
  log.Commit();
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("walls.lcm"), EvalOptions(), &input);
  ASSERT_EQ(input.static_segments.size(), 1u);
  EXPECT_EQ(input.static_segments[0].kind, TruthKind::kWall);
  EXPECT_EQ(input.static_segments[0].to_m, Eigen::Vector2d(6.0, 4.0));
  ASSERT_TRUE(r.map.has_value());
  EXPECT_EQ(r.map->num_static_truth, 1);  // the post; the wall is no point landmark
  const std::string map_svg = MapSvg(r);
  EXPECT_NE(map_svg.find("walls (truth)"), std::string::npos);
  EXPECT_EQ(MapSvg(Evaluate(input, EvalOptions())), map_svg);
}

// Three scans with LASER_SCAN and FEATURES: 0, 2 and 1 person features. The snapshot is scan 1
// (the most people), with its beams and lines; it is drawn in the truth frame from the robot's
// true pose plus the mount (robot at (1, 2) heading 90 degrees, sensor 0.5 m ahead: (1, 2.5)).
// Without a mount in the configuration, the log's LASER_GEOMETRY gives it, yaw included.
TEST(EvalPeopleTest, TheScanWithTheMostPeopleIsSnapshotAndDrawn) {
  testing::TempDir dir;
  LogWriter log(dir.File("snapshot.lcm"));
  slammtt_msgs::laser_geometry_t geometry{};
  geometry.utime = At(0);
  geometry.mount_forward_m = 0.3;
  geometry.mount_yaw_rad = M_PI / 2;
  geometry.view_start_rad = -M_PI;
  geometry.view_end_rad = M_PI;
  geometry.range_max_m = 10.0;
  log.WriteMessage(geometry.utime, "LASER_GEOMETRY", geometry);
  for (int k = 0; k < 3; ++k) {
    slammtt_msgs::laser_scan_t scan{};
    scan.utime = At(k);
    scan.range_max_m = 10.0f;
    scan.angle_rad = {0.0f, 0.5f, 1.0f};
    scan.range_m = {2.0f, 2.0f + k, 0.0f};
    scan.intensity = {1.0f, 1.0f, 0.0f};
    scan.valid = {1, 1, 0};
    scan.num_beams = 3;
    log.WriteMessage(scan.utime, "LASER_SCAN", scan);
    slammtt_msgs::features_t features{};
    features.utime = At(k);
    for (int f = 0; f < 2; ++f) {
      slammtt_msgs::feature_t point{};
      point.range_m = 2.0;
      point.bearing_rad = 0.1 * f;
      point.width_m = 0.1;
      point.leg_likeness = 0.9;
      features.features.push_back(point);
    }
    features.num_features = 2;
    slammtt_msgs::line_feature_t line{};
    line.first_x_m = 3.0;
    line.first_y_m = -1.0;
    line.last_x_m = 3.0;
    line.last_y_m = 1.0;
    features.lines = {line};
    features.num_lines = 1;
    const int people = k == 1 ? 2 : k == 2 ? 1 : 0;
    for (int q = 0; q < people; ++q) {
      slammtt_msgs::person_feature_t person{};
      person.range_m = 2.0;
      person.bearing_rad = 0.05;
      person.num_legs = 1;
      person.leg_index[0] = q;
      person.leg_index[1] = -1;
      features.people.push_back(person);
    }
    features.num_people = people;
    log.WriteMessage(features.utime, "FEATURES", features);
    slammtt_msgs::ground_truth_t gt{};
    gt.utime = At(k);
    gt.robot_x_m = 1.0;
    gt.robot_y_m = 2.0;
    gt.robot_heading_rad = M_PI / 2;
    log.WriteMessage(gt.utime, "GROUND_TRUTH", gt);
  }
  log.Commit();
  EvalOptions options;
  options.sensor_forward_m = 0.5;
  options.sensor_mount_given = true;
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("snapshot.lcm"), options, &input);
  ASSERT_TRUE(input.snapshot.has_value());
  EXPECT_EQ(input.snapshot->utime, At(1));
  EXPECT_EQ(input.snapshot->people.size(), 2u);
  ASSERT_EQ(input.snapshot->beams_m.size(), 2u);  // the invalid beam is left out
  EXPECT_NEAR(input.snapshot->beams_m[1].norm(), 3.0, 1e-6);  // scan 1's second beam
  ASSERT_TRUE(r.scan_picture.has_value());
  ASSERT_TRUE(r.scan_picture->sensor_pose.has_value());
  EXPECT_NEAR(r.scan_picture->sensor_pose->x_m, 1.0, 1e-12);
  EXPECT_NEAR(r.scan_picture->sensor_pose->y_m, 2.5, 1e-12);
  options.sensor_mount_given = false;  // the log's: 0.3 m ahead, turned by 90 degrees
  const EvaluationReport logged = Evaluate(input, options);
  ASSERT_TRUE(logged.scan_picture && logged.scan_picture->sensor_pose);
  EXPECT_NEAR(logged.scan_picture->sensor_pose->x_m, 1.0, 1e-12);
  EXPECT_NEAR(logged.scan_picture->sensor_pose->y_m, 2.3, 1e-12);
  EXPECT_NEAR(std::abs(logged.scan_picture->sensor_pose->heading_rad), M_PI, 1e-12);
  const std::string svg = ScanSvg(r);
  EXPECT_NE(svg.find("2 people"), std::string::npos);
  EXPECT_NE(svg.find("truth frame"), std::string::npos);
  EXPECT_NE(ScanSvg(EvaluationReport()).find("no LASER_SCAN"), std::string::npos);
}

TEST(EvalVisibilityTest, ANegativeBeamCountRejectsTheScan) {
  testing::TempDir dir;
  LogWriter log(dir.File("bad.lcm"));
  WriteScan(&log, 0, {Truth(10, 5, 0, true, 1.0, 5, true)}, {}, true);
  WriteScan(&log, 1, {Truth(10, 5, 0, true, 1.0, -1, false)}, {}, true);
  log.Commit();
  LogReadResult read;
  const EvalInput input = ReadEvalInput(dir.File("bad.lcm"), Channels(), &read);
  EXPECT_EQ(input.truth.size(), 1u);
  EXPECT_EQ(input.rejected.at("ground_truth"), 1);
  const EvaluationReport r = Evaluate(input, EvalOptions());
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].find("negative beam count"), std::string::npos) << r.notes[0];
}

// Eight scans of a feature log. Mover 20 stands at (3, 0) at scans 0-3 (0.1 m/s: a sway below
// the 0.2 m/s threshold), then walks at 1 m/s from scan 4. Track 200 sits on it throughout,
// labelled undecided (0-1), static (2-4), moving (5-7). At scan 1 a moving track 201 is 0.5 m
// from it, and at scan 3 a moving track 202 is 0.3 m from it and 203 is 0.6 m from it.
void WriteStandThenWalkLog(const std::string& path) {
  LogWriter log(path);
  const int8_t labels[8] = {Trk::CLASS_UNDECIDED, Trk::CLASS_UNDECIDED, Trk::CLASS_STATIC,
                            Trk::CLASS_STATIC,    Trk::CLASS_STATIC,    Trk::CLASS_MOVING,
                            Trk::CLASS_MOVING,    Trk::CLASS_MOVING};
  for (int k = 0; k < 8; ++k) {
    const bool standing = k < 4;
    const double x = standing ? 3.0 : 3.0 + 0.125 * (k - 4);
    std::vector<Trk> tracks = {Track(200, x, 0.0, labels[k])};
    if (k == 1) tracks.push_back(Track(201, x, 0.5, Trk::CLASS_MOVING));
    if (k == 3) {
      tracks.push_back(Track(202, x, 0.3, Trk::CLASS_MOVING));
      tracks.push_back(Track(203, x, -0.6, Trk::CLASS_MOVING));
    }
    WriteScan(&log, k, {Truth(20, x, 0, true, standing ? 0.1 : 1.0, 9, true)}, tracks, false);
  }
  log.Commit();
}

TEST(EvalStandingTest, AMoverThatStandsThenWalksIsScoredOnlyWhileItWalks) {
  // Truth set: scans 4-7 (GT 4). Scan 4: 200 is static, so no moving track: a miss. Scans 5-7:
  // 200 matched (3). Scan 1: 201 goes to the standing mover: excused. Scan 3: the standing mover
  // excuses one track, the nearer 202; 203 is a false positive. No switch (201 and 202 never
  // became the mover's correspondence), no fragmentation (never tracked before scan 5).
  // MOTA = 1 - (1 + 1 + 0) / 4 = 0.5.
  // Classification: first sighting = scan 4 (visible while moving); judged matched labels
  // static (4), moving (5-7): settles at scan 5, delay one scan, 1 visible scan before.
  testing::TempDir dir;
  WriteStandThenWalkLog(dir.File("stand.lcm"));
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("stand.lcm"), EvalOptions(), &input);
  ASSERT_TRUE(r.tracking.has_value());
  const TrackingResult& t = *r.tracking;
  EXPECT_EQ(t.clear_mot.num_truth, 4);
  EXPECT_EQ(t.clear_mot.num_matches, 3);
  EXPECT_EQ(t.clear_mot.num_misses, 1);
  EXPECT_EQ(t.clear_mot.num_false_positives, 1);
  EXPECT_EQ(t.clear_mot.num_id_switches, 0);
  EXPECT_EQ(t.clear_mot.num_fragmentations, 0);
  EXPECT_EQ(t.clear_mot.num_dont_care_objects, 2);
  EXPECT_DOUBLE_EQ(*t.clear_mot.mota, 0.5);
  EXPECT_EQ(t.mover_scans_standing, 4);
  EXPECT_EQ(t.movers_standing, 1);
  ASSERT_EQ(t.scans.size(), 8u);
  EXPECT_EQ(t.scans[1].num_truth, 0);
  EXPECT_EQ(t.scans[1].num_standing, 1);
  EXPECT_DOUBLE_EQ(t.scans[1].ospa_m, 0.0);  // 201 excused: both sets empty
  EXPECT_DOUBLE_EQ(t.scans[3].ospa_m, 1.0);  // 203 is a false object: OSPA = c
  ASSERT_TRUE(r.classification.has_value());
  ASSERT_EQ(r.classification->objects.size(), 1u);
  const ObjectClassification& o = r.classification->objects[0];
  EXPECT_EQ(o.first_visible_utime, At(4));
  EXPECT_EQ(o.final_label, ObjectLabel::kMoving);
  EXPECT_NEAR(*o.delay_s, kScanUs * 1e-6, 1e-12);
  EXPECT_EQ(*o.visible_scans_until_right, 1);

  const nlohmann::json j = ReportToJson(input, r);
  EXPECT_EQ(j["detail"]["tracking"]["dont_care"]["mover_scans_standing"], 4);
  EXPECT_EQ(j["detail"]["tracking"]["dont_care"]["tracks_on_standing_movers"], 2);
  EXPECT_EQ(j["detail"]["tracking"]["per_scan"]["standing"],
            nlohmann::json::array({1, 1, 1, 1, 0, 0, 0, 0}));
  EXPECT_DOUBLE_EQ(j["detail"]["options"]["min_moving_speed_mps"].get<double>(), 0.2);

  // With the rule off (speed 0) the standing scans count: GT 8. Hypotheses: 201 (scan 1),
  // 202 and 203 (scan 3), 200 (scans 5-7). Scan 1: 201 matched. Scan 3: 202 matched (Hungarian,
  // the nearer; 201 is gone), a switch 201 -> 202; 203 false. Scans 0, 2, 4: misses. Scan 5:
  // 200 matched, a switch 202 -> 200.
  // Fragmentations: tracked at 1, untracked at 2, back at 3; untracked at 4, back at 5: two.
  // MOTA = 1 - (3 misses + 1 false + 2 switches) / 8 = 0.25. Classification from scan 0: labels
  // U U S S S M M M (200 is the nearest track at every scan): settles at scan 5, 5 scans.
  EvalOptions off;
  off.min_moving_speed_mps = 0.0;
  const EvaluationReport r0 = Evaluate(input, off);
  EXPECT_EQ(r0.tracking->clear_mot.num_truth, 8);
  EXPECT_EQ(r0.tracking->clear_mot.num_misses, 3);
  EXPECT_EQ(r0.tracking->clear_mot.num_false_positives, 1);
  EXPECT_EQ(r0.tracking->clear_mot.num_id_switches, 2);
  EXPECT_EQ(r0.tracking->clear_mot.num_fragmentations, 2);
  EXPECT_DOUBLE_EQ(*r0.tracking->clear_mot.mota, 0.25);
  EXPECT_NEAR(*r0.classification->objects[0].delay_s, 5 * kScanUs * 1e-6, 1e-12);
  EXPECT_EQ(r0.tracking->mover_scans_standing, 0);
}

TEST(EvalEventsTest, ListsEachIdentitySwitchAndFragmentationWithItsTime) {
  // The five-scan hand-built log (hand_built_log.h): mover 10 changes track 100 -> 102 at scan
  // 4; mover 11 loses track 101 at scan 3 and gets it back at scan 4.
  testing::TempDir dir;
  testing::WriteHandBuiltLog(dir.File("run.lcm"), true);
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("run.lcm"), EvalOptions(), &input);
  const nlohmann::json j = ReportToJson(input, r);
  const nlohmann::json& switches = j["detail"]["tracking"]["identity_switch_events"];
  ASSERT_EQ(switches.size(), 1u);
  EXPECT_EQ(switches[0]["utime"], testing::ScanTime(4));
  EXPECT_EQ(switches[0]["truth_id"], 10);
  EXPECT_EQ(switches[0]["previous_track_id"], 100);
  EXPECT_EQ(switches[0]["new_track_id"], 102);
  const nlohmann::json& fragmentations = j["detail"]["tracking"]["fragmentation_events"];
  ASSERT_EQ(fragmentations.size(), 1u);
  EXPECT_EQ(fragmentations[0]["utime"], testing::ScanTime(4));
  EXPECT_EQ(fragmentations[0]["untracked_since_utime"], testing::ScanTime(3));
  EXPECT_EQ(fragmentations[0]["truth_id"], 11);
  EXPECT_EQ(fragmentations[0]["previous_track_id"], 101);
  EXPECT_EQ(fragmentations[0]["new_track_id"], 101);
  // What a test of "no identity switch through the occlusion" does: count the events in a time
  // window. Scans 0-3: none; scans 3-4: one.
  auto switches_between = [&](int64_t from, int64_t to) {
    int n = 0;
    for (const nlohmann::json& e : switches) {
      const int64_t t = e["utime"].get<int64_t>();
      n += (t >= from && t <= to) ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(switches_between(testing::ScanTime(0), testing::ScanTime(3)), 0);
  EXPECT_EQ(switches_between(testing::ScanTime(3), testing::ScanTime(4)), 1);
}

TEST(EvalOptionsTest, ReadsTheVisibilityAndStandingRules) {
  const EvalOptions defaults = ReadEvalOptions(Config());
  EXPECT_EQ(defaults.min_beams, 3);
  EXPECT_DOUBLE_EQ(defaults.min_moving_speed_mps, 0.2);
  const EvalOptions o = ReadEvalOptions(
      Config::FromString("eval:\n  min_beams: 5\n  min_moving_speed_mps: 0\n").Child("eval"));
  EXPECT_EQ(o.min_beams, 5);
  EXPECT_DOUBLE_EQ(o.min_moving_speed_mps, 0.0);
  // Bad values of these keys: EvalOptionsTest.ReadsTheEvalSectionAndNamesBadKeys (eval_test.cc).
  EvalInput input;
  EvalOptions bad;
  bad.min_beams = 0;
  EXPECT_THROW(Evaluate(input, bad), std::invalid_argument);
  bad = EvalOptions();
  bad.min_moving_speed_mps = -1.0;
  EXPECT_THROW(Evaluate(input, bad), std::invalid_argument);
}

// min_beams follows segmenter.min_points unless the eval section sets it: eval.min_beams, then
// segmenter.min_points, then 3 (the command line, tested below, comes before all of them).
TEST(EvalOptionsTest, MinBeamsFollowsTheSegmentersMinPoints) {
  EXPECT_EQ(ReadStackEvalOptions(Config()).min_beams, 3);
  EXPECT_EQ(ReadStackEvalOptions(Config::FromString("segmenter:\n  min_points: 5\n")).min_beams,
            5);
  EXPECT_EQ(ReadStackEvalOptions(Config::FromString("segmenter:\n  min_points: 5\n"
                                                    "eval:\n  min_beams: 4\n"))
                .min_beams,
            4);
  EXPECT_EQ(ReadStackEvalOptions(Config::FromString("segmenter:\n  lambda_deg: 15\n"
                                                    "eval:\n  min_moving_speed_mps: 0\n"))
                .min_beams,
            3);
  // The rest of the eval section is read as ReadEvalOptions reads it.
  const EvalOptions o = ReadStackEvalOptions(
      Config::FromString("segmenter:\n  min_points: 2\neval:\n  match_threshold_m: 0.5\n"));
  EXPECT_EQ(o.min_beams, 2);
  EXPECT_DOUBLE_EQ(o.match_threshold_m, 0.5);
  EXPECT_THROW(ReadStackEvalOptions(Config::FromString("eval:\n  min_beam: 2\n")), ConfigError);
  // A bad min_points is an error naming it (the segmenter would reject it too).
  for (const std::string bad : {"0", "2.5", "1000000", "three"}) {
    try {
      ReadStackEvalOptions(
          Config::FromString("segmenter:\n  min_points: " + bad + "\n", "stack.yaml"));
      ADD_FAILURE() << "accepted min_points " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("stack.yaml:2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("segmenter.min_points"), std::string::npos)
          << e.what();
    }
  }
  // With eval.min_beams set, segmenter.min_points is not the evaluation's business.
  EXPECT_EQ(ReadStackEvalOptions(Config::FromString("segmenter:\n  min_points: 0\n"
                                                    "eval:\n  min_beams: 3\n"))
                .min_beams,
            3);
}

TEST(EvalProgramTest, MinBeamsFollowsTheSegmenterSectionOfTheConfig) {
  testing::TempDir dir;
  WriteTwoBeamLog(dir.File("scans.lcm"), true);
  const std::string program = std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval ";
  const std::string config = dir.File("stack.yaml");
  testing::WriteFileBytes(config, "segmenter:\n  min_points: 2\n");
  int status = 0;
  std::string out = RunCommand(program + dir.File("scans.lcm") + " --config " + config +
                                   " --json " + dir.File("two.json") + " 2>&1",
                               &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json two = nlohmann::json::parse(testing::FileBytes(dir.File("two.json")));
  EXPECT_EQ(two["detail"]["options"]["min_beams"], 2);
  EXPECT_DOUBLE_EQ(two["mota"].get<double>(), 0.75);  // as with --min-beams 2 below
  // The command line still wins.
  out = RunCommand(program + dir.File("scans.lcm") + " --config " + config + " --min-beams 3" +
                       " --json " + dir.File("three.json") + " 2>&1",
                   &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json three = nlohmann::json::parse(testing::FileBytes(dir.File("three.json")));
  EXPECT_EQ(three["detail"]["options"]["min_beams"], 3);
  EXPECT_DOUBLE_EQ(three["mota"].get<double>(), 1.0);
  // A bad value is a one-line error naming the key, and no report.
  testing::WriteFileBytes(config, "segmenter:\n  min_points: 0\n");
  out = RunCommand(program + dir.File("scans.lcm") + " --config " + config + " --json " +
                       dir.File("bad.json") + " 2>&1",
                   &status);
  EXPECT_NE(status, 0) << out;
  EXPECT_NE(out.find("segmenter.min_points"), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_FALSE(testing::FileExists(dir.File("bad.json")));
}

TEST(EvalProgramTest, CommandLineOverridesTheRules) {
  testing::TempDir dir;
  WriteTwoBeamLog(dir.File("scans.lcm"), true);
  const std::string program = std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval ";
  const std::string config = dir.File("stack.yaml");
  testing::WriteFileBytes(config, "eval:\n  min_beams: 3\n");
  int status = 0;
  std::string out = RunCommand(program + dir.File("scans.lcm") + " --config " + config +
                                   " --min-beams 2 --json " + dir.File("two.json") + " 2>&1",
                               &status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("don't care:"), std::string::npos) << out;
  const nlohmann::json two = nlohmann::json::parse(testing::FileBytes(dir.File("two.json")));
  EXPECT_DOUBLE_EQ(two["mota"].get<double>(), 0.75);  // the command line won over the file
  EXPECT_EQ(two["detail"]["options"]["min_beams"], 2);

  out = RunCommand(program + dir.File("scans.lcm") + " --config " + config + " --json " +
                       dir.File("three.json") + " 2>&1",
                   &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json three = nlohmann::json::parse(testing::FileBytes(dir.File("three.json")));
  EXPECT_DOUBLE_EQ(three["mota"].get<double>(), 1.0);

  for (const std::string bad : {"--min-beams 0", "--min-moving-speed-mps=-1",
                                "--min-beams two"}) {
    out = RunCommand(program + dir.File("scans.lcm") + " " + bad + " --json " +
                         dir.File("bad.json") + " 2>&1",
                     &status);
    EXPECT_NE(status, 0) << bad;
    EXPECT_NE(out.find(bad.substr(0, bad.find_first_of(" ="))), std::string::npos) << out;
    EXPECT_FALSE(testing::FileExists(dir.File("bad.json"))) << bad;
  }
}

// Honest reporting: mover 10 walks at 1 m/s, visible at scans 0-3, followed by track 100, which
// is measured (reported) at scans 0-1 and coasts at scans 2-3 (confirmed, not reported). The
// score takes reported tracks: 2 matches, 2 misses of 4, MOTA 0.5; with coasting tracks: 4
// matches, MOTA 1.
TEST(EvalReportingTest, ReportedTracksAreScoredAndCoastingOnesBeside) {
  testing::TempDir dir;
  LogWriter log(dir.File("coast.lcm"));
  for (int k = 0; k < 4; ++k) {
    const double x = 5.0 + 0.125 * k;
    Trk track = Track(100, x, 2, Trk::CLASS_MOVING);
    track.reported = k < 2;
    track.measured = k < 2;
    track.coasting_s = k < 2 ? 0.0 : (k - 1) * kScanUs * 1e-6;
    WriteScan(&log, k, {Truth(10, x, 2, true, 1.0, 5, true)}, {track}, false);
  }
  log.Commit();
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("coast.lcm"), EvalOptions(), &input);
  ASSERT_TRUE(r.tracking.has_value());
  ASSERT_TRUE(r.tracking_with_coasting.has_value());
  EXPECT_EQ(r.tracking->clear_mot.num_matches, 2);
  EXPECT_EQ(r.tracking->clear_mot.num_misses, 2);
  EXPECT_DOUBLE_EQ(*r.tracking->clear_mot.mota, 0.5);
  EXPECT_EQ(r.tracking_with_coasting->clear_mot.num_matches, 4);
  EXPECT_DOUBLE_EQ(*r.tracking_with_coasting->clear_mot.mota, 1.0);
  EXPECT_TRUE(input.tracks[3].tracks[0].confirmed);
  EXPECT_FALSE(input.tracks[3].tracks[0].reported);
  EXPECT_NEAR(input.tracks[3].tracks[0].coasting_s, 0.25, 1e-12);
  const nlohmann::json j = ReportToJson(input, r);
  EXPECT_DOUBLE_EQ(j["mota"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["mota_with_coasting"].get<double>(), 1.0);
}

// A person (20) stands still at scans 0-3 and is tracked by 120, a STATIC track of kind PERSON;
// 121 is a STATIC landmark of kind OTHER beside it. The rule-based score excuses a standing
// mover (no truth: MOTA undefined); the people score counts the person at every scan and takes
// tracks of kind PERSON whatever their class: 4 matches of 4, MOTA 1, and 121 is no track.
TEST(EvalReportingTest, AStandingPersonCountsInThePeopleScore) {
  testing::TempDir dir;
  LogWriter log(dir.File("standing.lcm"));
  for (int k = 0; k < 4; ++k) {
    Obj person = Person(20, 5, 1, 6);
    person.vx_mps = 0.0;
    Trk track = Track(120, 5, 1, Trk::CLASS_STATIC);
    track.kind = Trk::KIND_PERSON;
    WriteScan(&log, k, {person}, {track, Track(121, 5.5, 1, Trk::CLASS_STATIC)}, false);
  }
  log.Commit();
  EvalInput input;
  const EvaluationReport r = EvaluateFile(dir.File("standing.lcm"), EvalOptions(), &input);
  ASSERT_TRUE(r.tracking.has_value());
  EXPECT_EQ(r.tracking->clear_mot.num_truth, 0);
  EXPECT_FALSE(r.tracking->clear_mot.mota.has_value());
  ASSERT_TRUE(r.people_tracking.has_value());
  EXPECT_EQ(r.people_tracking->clear_mot.num_truth, 4);
  EXPECT_EQ(r.people_tracking->clear_mot.num_matches, 4);
  EXPECT_EQ(r.people_tracking->clear_mot.num_false_positives, 0);
  EXPECT_DOUBLE_EQ(*r.people_tracking->clear_mot.mota, 1.0);
  const nlohmann::json j = ReportToJson(input, r);
  EXPECT_DOUBLE_EQ(j["people_mota"].get<double>(), 1.0);
  EXPECT_EQ(j["people_id_switches"], 0);
}

}  // namespace
}  // namespace slammtt
