// The filter's local window of static landmarks (estimator/landmark_window.h): far confirmed
// static landmarks leave the state with their id, mean and marginal covariance; they come back
// under the same id, uncorrelated, when the robot does; the budget keeps the farthest out;
// without a window nothing changes; and over a whole loop driven by the estimator no landmark
// is lost or mapped twice.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "estimator/estimator.h"
#include "estimator/gating.h"
#include "estimator/landmark_window.h"
#include "estimator/observation_predictions.h"
#include "estimator/pruning.h"
#include "estimator/scan_gating.h"
#include "estimator/track_management.h"
#include "estimator/testing/point_world.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::StepScene;
using testing::WorldFrame;
using testing::WorldObject;

LandmarkWindowOptions Window(double radius_m, double reenter_radius_m, int max_landmarks = 0) {
  LandmarkWindowOptions window;
  window.radius_m = radius_m;
  window.reenter_radius_m = reenter_radius_m;
  window.max_landmarks = max_landmarks;
  return window;
}

// A robot known to 1 mm with landmarks correlated with it and each other, as a filter's are.
StepScene CorrelatedScene() {
  StepScene scene;
  scene.state.covariance().topLeftCorner<3, 3>() = Eigen::Vector3d(0.04, 0.04, 1e-3).asDiagonal();
  Eigen::Matrix<double, 2, 3> g;
  g << 1, 0, 0.2, 0, 1, -0.3;
  ObjectRecord record;
  record.object_class = ObjectClass::kStatic;
  record.confirmed = true;
  const Eigen::Vector2d positions[] = {{10, 0}, {50, 5}, {-60, 0}, {20, 20}};
  for (int k = 0; k < 4; ++k) {
    record.id = 101 + k;
    record.hits = 7 + k;
    record.num_offsets = 2;
    record.unseen_in_view_s = 0.5;
    scene.state.AddObject(positions[k], g, 0.01 * Eigen::Matrix2d::Identity(), record);
  }
  return scene;
}

TEST(LandmarkWindowTest, FarConfirmedStaticLandmarksLeaveWithTheirIdMeanAndMarginal) {
  StepScene scene = CorrelatedScene();
  const int mover = scene.AddMover({70, 0}, 0.1, {1, 0}, 0.1, ObjectClass::kMoving, 201);
  const int undecided = scene.AddMover({0, 80}, 0.1, {0, 0}, 0.1, ObjectClass::kUndecided, 202);
  const int tentative = scene.AddLandmark({0, -90}, 0.1, 203);
  scene.state.object(tentative).record.confirmed = false;
  const int person = scene.AddLandmark({90, 0}, 0.1, 204);
  scene.state.object(person).record.kind = ObjectKind::kPerson;
  (void)mover;
  (void)undecided;
  const SlamState before = scene.state;

  LandmarkArchive archive;
  EXPECT_EQ(archive.Archive(Window(40, 35), &scene.state), 2);
  // 102 (50 m) and 103 (60 m) left; the near landmarks and every object that is not a
  // confirmed static landmark of kind OTHER stayed, in their order.
  ASSERT_EQ(archive.size(), 2);
  std::vector<int64_t> ids;
  for (const StateObject& o : scene.state.objects()) ids.push_back(o.record.id);
  EXPECT_EQ(ids, (std::vector<int64_t>{101, 104, 201, 202, 203, 204}));
  for (const int k : {1, 2}) {
    const ArchivedLandmark& a = archive.landmarks().at(before.object(k).record.id);
    EXPECT_EQ(a.position_m, before.position(k));
    EXPECT_EQ(a.covariance_m2, Eigen::Matrix2d(before.ObjectCovariance(k).block(0, 0, 2, 2)));
    EXPECT_EQ(a.record.hits, before.object(k).record.hits);
  }
  // The rest of the state is the marginal of what it was: the robot's block unchanged.
  EXPECT_EQ(scene.state.robot_covariance(), before.robot_covariance());
  EXPECT_EQ(scene.state.ObjectCovariance(1), before.ObjectCovariance(3));
  // Nothing else is far: a second pass moves nothing.
  EXPECT_EQ(archive.Archive(Window(40, 35), &scene.state), 0);
}

TEST(LandmarkWindowTest, AnArchivedLandmarkReentersUnderItsIdUncorrelatedWhenTheRobotComesBack) {
  StepScene scene = CorrelatedScene();
  LandmarkArchive archive;
  ASSERT_EQ(archive.Archive(Window(40, 35), &scene.state), 2);
  const ArchivedLandmark archived = archive.landmarks().at(102);
  // Still 20 m beyond the re-entry radius: stays out.
  EXPECT_EQ(archive.Restore(Window(40, 35), &scene.state), 0);
  scene.state.mean()(0) = 20.0;  // the robot drove towards it: 30.4 m away
  EXPECT_EQ(archive.Restore(Window(40, 35), &scene.state), 1);
  EXPECT_EQ(archive.size(), 1);
  EXPECT_EQ(archive.landmarks().count(103), 1u);
  const int k = scene.state.num_objects() - 1;
  const StateObject& back = scene.state.object(k);
  EXPECT_EQ(back.record.id, 102);
  EXPECT_FALSE(back.has_velocity());
  EXPECT_EQ(back.record.object_class, ObjectClass::kStatic);
  EXPECT_TRUE(back.record.confirmed);
  EXPECT_EQ(back.record.hits, archived.record.hits);
  EXPECT_EQ(back.record.num_offsets, 0);  // the classifier's evidence starts again
  EXPECT_EQ(back.record.unseen_in_view_s, 0.0);
  EXPECT_EQ(scene.state.position(k), archived.position_m);
  const int p = back.position_index;
  EXPECT_EQ(Eigen::Matrix2d(scene.state.covariance().block<2, 2>(p, p)), archived.covariance_m2);
  EXPECT_TRUE(scene.state.covariance().block(p, 0, 2, p).isZero(0.0));
  EXPECT_TRUE(scene.state.covariance().block(0, p, p, 2).isZero(0.0));
}

// A re-entered landmark just beyond the laser's range must not take the measurement of a post
// nearer than it (large-loop seed 1: a post 1.1 m nearer, at 30.0 m, moved the robot by 0.5 m):
// until its first measurement after re-entry it is judged only where it is surely in range.
TEST(LandmarkWindowTest, AReenteredLandmarkIsJudgedOnlyWhereItIsSurelyInRange) {
  StepScene scene;
  scene.AddLandmark({31, 0}, 0.5, 102);  // 2 sigma of its range: 1 m
  scene.AddLandmark({-31, 0.5}, 0.5, 103);
  LandmarkArchive archive;
  scene.state.mean()(0) = 80.0;  // 49 m from 102: it leaves, and 103 (111 m) too
  ASSERT_EQ(archive.Archive(Window(40, 33), &scene.state), 2);
  scene.state.mean()(0) = 0.0;  // back: both within 33 m
  ASSERT_EQ(archive.Restore(Window(40, 33), &scene.state), 2);
  // 103 as if it had been measured since: only landmarks unseen since re-entry are held back.
  int reentered = -1;
  for (int j = 0; j < scene.state.num_objects(); ++j) {
    if (scene.state.object(j).record.id == 102) reentered = j;
    if (scene.state.object(j).record.id == 103) {
      scene.state.object(j).record.reentered_unseen = false;
    }
  }
  ASSERT_GE(reentered, 0);
  EXPECT_TRUE(scene.state.object(reentered).record.reentered_unseen);

  const FieldOfView all_around;  // the full circle
  PointMeasurement nearer_post;  // 1 m nearer than 102, in its bearing
  nearer_post.range_bearing << 30.0 - 0.1, 0.0;
  nearer_post.covariance = Eigen::Vector2d(0.04, 1.2e-3).asDiagonal();
  const std::vector<PointMeasurement> measurements{nearer_post};

  // Without the hold-back the nearer post's measurement falls in the landmark's gate (the
  // failure this rule prevents).
  ObservationPredictions plain(scene.options.sensor);
  bool paired = false;
  for (const Candidate& c : GatePairs(measurements, plain.At(scene.state), 13.82)) {
    paired = paired || c.object == reentered;
  }
  EXPECT_TRUE(paired);

  // With it: 31 m + 1 m is beyond 30 m, no pair; 103 (never archived in this story) is judged.
  ObservationPredictions held(scene.options.sensor);
  held.HoldBackReentriesBeyond(30.0, all_around);
  const std::vector<ObjectPrediction>& beyond = held.At(scene.state);
  EXPECT_FALSE(beyond[static_cast<size_t>(reentered)].valid);
  for (int j = 0; j < scene.state.num_objects(); ++j) {
    if (j != reentered) {
      EXPECT_TRUE(beyond[static_cast<size_t>(j)].valid) << j;
    }
  }
  for (const Candidate& c : GatePairs(measurements, beyond, 13.82)) {
    EXPECT_NE(c.object, reentered);
  }
  // ... but the measurement starts no new object either (it may be 102, seen before it is
  // surely in range: a second landmark for the same post): its nearest NIS is the held-back
  // landmark's, below the new-object gate, while it is in no pair of the scan.
  EXPECT_TRUE(beyond[static_cast<size_t>(reentered)].held_back);
  const ScanGating gated = GateScan(measurements, beyond, scene.options);
  EXPECT_LT(gated.nearest_nis[0], scene.options.new_object_gate_dn_chi2);
  for (const Candidate& c : gated.gated) EXPECT_NE(c.object, reentered);
  // A measurement far from every landmark still starts one.
  PointMeasurement elsewhere = nearer_post;
  elsewhere.range_bearing << 20.0, 1.5;
  EXPECT_EQ(GateScan({elsewhere}, beyond, scene.options).nearest_nis[0],
            std::numeric_limits<double>::infinity());

  // Nearer (28 m + 1 m within 30 m): judged again.
  scene.state.mean()(0) = 3.0;
  EXPECT_TRUE(held.At(scene.state)[static_cast<size_t>(reentered)].valid);

  // Once measured after re-entry it is an ordinary landmark again, wherever it is.
  scene.state.mean()(0) = 0.0;
  EXPECT_FALSE(held.At(scene.state)[static_cast<size_t>(reentered)].valid);
  RecordHit(1, TrackManagementOptions{}, &scene.state.object(reentered).record);
  EXPECT_FALSE(scene.state.object(reentered).record.reentered_unseen);
  scene.state.mean()(1) = 1e-9;  // a new revision of the state: predicted again
  EXPECT_TRUE(held.At(scene.state)[static_cast<size_t>(reentered)].valid);
}

TEST(LandmarkWindowTest, TheBudgetKeepsTheNearestAndDoesNotLetTheOthersBackIn) {
  StepScene scene;
  for (int k = 0; k < 5; ++k) scene.AddLandmark({2.0 + 3.0 * k, 0.0}, 0.1, 11 + k);
  LandmarkArchive archive;
  EXPECT_EQ(archive.Archive(Window(40, 35, 3), &scene.state), 2);
  EXPECT_EQ(scene.state.num_objects(), 3);
  EXPECT_EQ(archive.landmarks().count(14), 1u);
  EXPECT_EQ(archive.landmarks().count(15), 1u);
  // Within the re-entry radius, but the state is full.
  EXPECT_EQ(archive.Restore(Window(40, 35, 3), &scene.state), 0);
  // One place free: the nearest archived landmark takes it.
  scene.state.RemoveObjects({0});
  EXPECT_EQ(archive.Restore(Window(40, 35, 3), &scene.state), 1);
  EXPECT_EQ(scene.state.object(scene.state.num_objects() - 1).record.id, 14);
}

TEST(LandmarkWindowTest, WithoutAWindowNothingMoves) {
  StepScene scene = CorrelatedScene();
  const SlamState before = scene.state;
  LandmarkArchive archive;
  EXPECT_EQ(archive.Archive(LandmarkWindowOptions{}, &scene.state), 0);
  EXPECT_EQ(archive.Restore(LandmarkWindowOptions{}, &scene.state), 0);
  EXPECT_EQ(scene.state.num_objects(), before.num_objects());
  EXPECT_EQ(scene.state.revision(), before.revision());
}

TEST(LandmarkWindowTest, OptionsThatCannotWorkAreRefusedByKey) {
  EXPECT_EQ(CheckLandmarkWindowOptions(LandmarkWindowOptions{}, 30), "");
  EXPECT_EQ(CheckLandmarkWindowOptions(Window(40, 35), 30), "");
  EXPECT_EQ(CheckLandmarkWindowOptions(Window(40, 45), 30),
            "window_reenter_radius_m must be <= window_radius_m");
  EXPECT_EQ(CheckLandmarkWindowOptions(Window(40, 25), 30).find("window_reenter_radius_m must "
                                                                "be >= max_range_m"),
            0u);
  EXPECT_EQ(CheckLandmarkWindowOptions(Window(0, 0, 10), 30),
            "window_max_landmarks needs window_radius_m > 0");
  EstimatorOptions options;
  options.window = Window(40, 25);
  EXPECT_NE(CheckEstimatorOptions(options).find("window_reenter_radius_m"), std::string::npos);
}

TEST(LandmarkWindowTest, WithAWindowAnUnseenStaticLandmarkGoesToTheArchiveInsteadOfAway) {
  for (const bool window : {false, true}) {
    StepScene scene;
    scene.options.window = window ? Window(40, 35) : LandmarkWindowOptions{};
    const int landmark = scene.AddLandmark({5, 0}, 0.1, 31);
    const int tentative = scene.AddLandmark({5, 2}, 0.1, 32);
    scene.state.object(tentative).record.confirmed = false;
    for (const int k : {landmark, tentative}) {
      scene.state.object(k).record.unseen_in_view_s = 10.0;  // beyond 3.5 s: pruned
      scene.state.object(k).record.last_seen_utime = -100 * testing::kSecond;
    }
    LandmarkArchive archive;
    PruneObjects(0, {}, scene.options, scene.Predictions(), Assignment(0, 2), &scene.state,
                 &scene.counts, &archive);
    EXPECT_EQ(scene.state.num_objects(), 0);
    EXPECT_EQ(scene.counts.pruned, window ? 1 : 2);
    EXPECT_EQ(scene.counts.landmarks_archived, window ? 1 : 0);
    EXPECT_EQ(archive.landmarks().count(31), window ? 1u : 0u);
    EXPECT_EQ(archive.landmarks().count(32), 0u);  // a tentative object is no landmark yet
  }
}

// Posts on both sides of a circle of radius 40 m, driven round once and 60 m more at 2 m/s
// with a 15 m sensor: the far side of the circle (80 m across) leaves the state and comes back.
std::vector<WorldObject> PostsAlongACircle(int count) {
  std::vector<WorldObject> objects;
  for (int k = 0; k < count; ++k) {
    const double angle = 2.0 * M_PI * k / count;
    const double radius = k % 2 == 0 ? 36.0 : 44.0;
    objects.push_back({k + 1, Eigen::Vector2d(radius * std::sin(angle),
                                              40.0 - radius * std::cos(angle)), {}, false});
  }
  return objects;
}

TEST(LandmarkWindowTest, OverALoopNoLandmarkIsLostOrMappedTwice) {
  PointWorldOptions world_options;
  world_options.max_range_m = 15.0;
  world_options.seed = 3;
  const double speed_mps = 2.0;
  PointWorld world(world_options, [&](double) { return Eigen::Vector2d(speed_mps, 0.05); },
                   PostsAlongACircle(120));
  EstimatorOptions options;
  options.max_range_m = 15.0;
  options.field_of_view_rad = world_options.field_of_view_rad;
  options.window = Window(22, 18);
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  const int scans = static_cast<int>((2.0 * M_PI * 40.0 + 60.0) / speed_mps * 8.0);
  int most_in_state = 0;
  int most_archived = 0;
  int restored = 0;
  std::set<int64_t> ever_mapped;
  ScanResult result;
  Eigen::Vector3d true_pose = Eigen::Vector3d::Zero();
  for (int i = 0; i < scans; ++i) {
    const WorldFrame frame = world.Next();
    for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
    result = estimator.ProcessScan(frame.scan, &rng);
    ASSERT_TRUE(result.processed);
    true_pose = frame.true_pose;
    most_in_state = std::max(most_in_state, estimator.state().num_objects());
    most_archived = std::max(most_archived, estimator.archive().size());
    restored += result.counts.landmarks_restored;
    for (const ObjectEstimate& e : result.objects) {
      if (e.object_class == ObjectClass::kStatic && e.confirmed) ever_mapped.insert(e.id);
    }
  }
  EXPECT_GT(most_archived, 60);
  EXPECT_LT(most_in_state, 50);
  EXPECT_GT(restored, 10);
  EXPECT_EQ(estimator.counters().object_cap_hits, 0);
  // Every landmark ever mapped is still in the map (state or archive), once.
  std::map<int64_t, Eigen::Vector2d> final_map;
  for (const ObjectEstimate& e : result.objects) {
    if (e.object_class == ObjectClass::kStatic && e.confirmed) final_map[e.id] = e.position;
  }
  for (const ObjectEstimate& e : result.archived_landmarks) {
    EXPECT_EQ(final_map.count(e.id), 0u) << "in the state and in the archive: " << e.id;
    final_map[e.id] = e.position;
  }
  for (const int64_t id : ever_mapped) EXPECT_EQ(final_map.count(id), 1u) << id;
  // One landmark per post: the loop closed on the old landmarks instead of starting new ones.
  // (The filter's map is as the filter left it: the far side, archived mid-loop, keeps its
  // drift of up to about 2 m; the smoother is what corrects it.)
  const std::vector<WorldObject> posts = PostsAlongACircle(120);
  std::map<int64_t, int> claimed;  // post id -> landmarks nearest to it
  double worst_m = 0.0;
  for (const auto& [id, position] : final_map) {
    const WorldObject* nearest = &posts.front();
    for (const WorldObject& post : posts) {
      if ((position - post.start_m).norm() < (position - nearest->start_m).norm()) {
        nearest = &post;
      }
    }
    ++claimed[nearest->id];
    worst_m = std::max(worst_m, (position - nearest->start_m).norm());
  }
  std::printf("map %zu landmarks for 120 posts, %zu posts claimed, worst %.2f m; at most %d in "
              "the state, %d archived, %d re-entries\n",
              final_map.size(), claimed.size(), worst_m, most_in_state, most_archived, restored);
  // With every landmark ever mapped still in the map (above), 120 means none was started twice;
  // a drifted landmark may lie nearer a neighbouring post than its own (4 m apart).
  EXPECT_EQ(final_map.size(), 120u);
  EXPECT_GE(claimed.size(), 114u);
  EXPECT_LT(worst_m, 3.0);
  EXPECT_LT((result.pose.head<2>() - true_pose.head<2>()).norm(), 1.5);
}

}  // namespace
}  // namespace slammtt
