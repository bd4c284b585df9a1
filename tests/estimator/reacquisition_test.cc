// Re-acquisition of lost movers (estimator/reacquisition.h: ChooseReacquisitions, IsLostMover,
// the two steps TagPossibleContinuations and TakeOverLostIdentities, and both through
// Estimator::ProcessScan): a person who walked out of a 180-degree view and comes back
// somewhere they can have walked to keeps their identity from the second measurement on; a
// measurement beyond walking reach, or one that an unmeasured static landmark has most likely
// produced, does not carry an identity.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/reacquisition.h"
#include "estimator/track_management.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;
constexpr int64_t kScan = kSecond / 8;  // 8 Hz
constexpr double kDegree = M_PI / 180.0;

TEST(ChooseReacquisitionsTest, OnlyBirthsWithinWalkingReachOfTheLastSighting) {
  // A track last seen at the origin 1.5 s ago: reachable within 2 m/s * 1.5 s = 3 m.
  const std::vector<LostTrack> lost = {{4, Eigen::Vector2d(0.0, 0.0), 1.5}};
  const std::vector<BirthPoint> births = {{0, Eigen::Vector2d(3.2, 0.0)},
                                          {1, Eigen::Vector2d(0.0, 2.9)}};
  const std::vector<Reacquisition> chosen = ChooseReacquisitions(lost, births, 2.0);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0].measurement, 1);
  EXPECT_EQ(chosen[0].object, 4);
  EXPECT_TRUE(ChooseReacquisitions(lost, births, 0.0).empty()) << "0 disables re-acquisition";
  EXPECT_TRUE(ChooseReacquisitions(lost, {{0, Eigen::Vector2d(3.01, 0.0)}}, 2.0).empty());
}

TEST(ChooseReacquisitionsTest, OneToOneInIncreasingShareOfTheReach) {
  // Track 7 (reach 4 m) and track 9 (reach 1 m); measurement 0 is 0.9 m from track 9 (0.9 of
  // its reach) and 1 m from track 7 (0.25 of its reach); measurement 1 is 0.5 m from track 9
  // and 1.4 m from track 7.
  const std::vector<LostTrack> lost = {{7, Eigen::Vector2d(0.0, 0.0), 2.0},
                                       {9, Eigen::Vector2d(1.9, 0.0), 0.5}};
  const std::vector<BirthPoint> births = {{0, Eigen::Vector2d(1.0, 0.0)},
                                          {1, Eigen::Vector2d(1.4, 0.0)}};
  const std::vector<Reacquisition> chosen = ChooseReacquisitions(lost, births, 2.0);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0].measurement, 0);  // 0.25 of track 7's reach: the closest fit
  EXPECT_EQ(chosen[0].object, 7);
  EXPECT_EQ(chosen[1].measurement, 1);  // track 7 is taken: track 9 at 0.5 of its reach
  EXPECT_EQ(chosen[1].object, 9);
}

// A lost mover (id 7: confirmed MOVING, last seen at (1, 1) 2 s ago, so reachable within 4 m;
// its estimate coasted to (6, 6)), a static landmark and a tentative object born at the
// previous scan as its possible continuation (id 20, continues_id 7, one hit).
struct LostMoverScene : testing::StepScene {
  int lost = -1;
  int landmark = -1;
  int candidate = -1;
  static constexpr int64_t kUtime = 2 * testing::kSecond;
  LostMoverScene() {
    lost = AddMover({6.0, 6.0}, 0.5, {1.0, 1.0}, 0.3, ObjectClass::kMoving, 7);
    ObjectRecord& r = state.object(lost).record;
    r.last_seen_m = Eigen::Vector2d(1.0, 1.0);
    r.first_seen_utime = 1;
    r.hits = 12;
    landmark = AddLandmark({3.0, -1.0}, 0.02);
    candidate = AddMover({1.0, 3.0}, 0.2, {0.0, 0.0}, 1.0, ObjectClass::kUndecided, 20);
    ObjectRecord& c = state.object(candidate).record;
    c.confirmed = false;
    c.continues_id = 7;
    c.hits = 1;
  }
  ScanAssociation Scan(const std::vector<uint8_t>& may_update) const {
    return ScanAssociation{measurements, may_update, kUtime};
  }
};

TEST(TagPossibleContinuationsTest, ABirthWithinReachOfALostMoverCarriesItsId) {
  LostMoverScene scene;
  ASSERT_TRUE(IsLostMover(scene.state.object(scene.lost), true, LostMoverScene::kUtime,
                          scene.options.tracks));
  scene.Measure({1.0, -2.5});   // 0: 3.5 m from the last sighting: within reach
  // 1: 17 cm behind the unmeasured landmark (NIS about 22: between dn and 2 dn), nearer the last
  // sighting than measurement 0, but most likely the landmark's: no identity.
  scene.Measure(Eigen::Vector2d(3.0, -1.0) + 0.17 * Eigen::Vector2d(3.0, -1.0).normalized());
  scene.Measure({1.0, -2.6});   // 2: assigned to something: not a birth
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const std::vector<double> nearest(3, std::numeric_limits<double>::infinity());
  Assignment assignment(3, 3);
  assignment.Set(2, scene.candidate);
  ObservationPredictions predicted(scene.options.sensor);
  const std::vector<int64_t> tags =
      TagPossibleContinuations(scene.Scan(may_update), nearest, {}, scene.options, &predicted,
                               scene.state, assignment);
  EXPECT_EQ(tags, (std::vector<int64_t>{7, 0, 0}));
  // Not for a track whose identity was taken over this scan, nor with re-acquisition off.
  EXPECT_EQ(TagPossibleContinuations(scene.Scan(may_update), nearest, {scene.lost}, scene.options,
                                     &predicted, scene.state, assignment),
            (std::vector<int64_t>{0, 0, 0}));
  scene.options.tracks.reacquire_speed_mps = 0.0;
  EXPECT_EQ(TagPossibleContinuations(scene.Scan(may_update), nearest, {}, scene.options,
                                     &predicted, scene.state, assignment),
            (std::vector<int64_t>{0, 0, 0}));
}

TEST(TakeOverLostIdentitiesTest, ATaggedObjectAtItsSecondHitTakesTheLostIdentity) {
  LostMoverScene scene;
  scene.state.object(scene.candidate).record.hits = 2;  // this scan's hit recorded
  Assignment assignment(1, 3);
  assignment.Set(0, scene.candidate);
  StepCounts counts;
  const std::vector<int> taken_over = TakeOverLostIdentities(
      LostMoverScene::kUtime, scene.options, assignment, &scene.state, &counts);
  EXPECT_EQ(taken_over, std::vector<int>{scene.lost});
  EXPECT_EQ(counts.reacquired, 1);
  const ObjectRecord& c = scene.state.object(scene.candidate).record;
  EXPECT_EQ(c.id, 7);
  EXPECT_EQ(c.first_seen_utime, 1);
  EXPECT_EQ(c.hits, 14);
  EXPECT_TRUE(c.confirmed);
  EXPECT_EQ(c.object_class, ObjectClass::kMoving);
  EXPECT_EQ(c.continues_id, 0);
}

TEST(TakeOverLostIdentitiesTest, NotWithoutAMeasurementNorWhenTheTrackIsFoundAgain) {
  {
    LostMoverScene scene;
    scene.state.object(scene.candidate).record.hits = 2;
    StepCounts counts;
    EXPECT_TRUE(TakeOverLostIdentities(LostMoverScene::kUtime, scene.options, Assignment(1, 3),
                                       &scene.state, &counts)
                    .empty());
    EXPECT_EQ(scene.state.object(scene.candidate).record.continues_id, 7) << "kept for later";
  }
  {
    LostMoverScene scene;
    scene.state.object(scene.candidate).record.hits = 2;
    Assignment assignment(2, 3);
    assignment.Set(0, scene.candidate);
    assignment.Set(1, scene.lost);  // the lost track got a measurement itself
    StepCounts counts;
    EXPECT_TRUE(TakeOverLostIdentities(LostMoverScene::kUtime, scene.options, assignment,
                                       &scene.state, &counts)
                    .empty());
    EXPECT_EQ(counts.reacquired, 0);
    EXPECT_EQ(scene.state.object(scene.candidate).record.id, 20);
    EXPECT_EQ(scene.state.object(scene.candidate).record.continues_id, 0) << "tried once";
  }
}

// A robot standing at the origin with a 180-degree view (+x ahead), exact odometry, two posts
// always in view. A walker starts at (3, 1.5) and walks at 1 m/s along -x until it leaves the
// view beside the robot (last seen at 2.875 s). It comes back `unseen_s` after its last
// sighting at `return_point`, standing there. `extra_post` (optional) is a third post; on the
// return scan it is not measured (the person stands in front of it). Returns each scan's result.
struct ReturnCase {
  double unseen_s = 1.5;
  Eigen::Vector2d return_point{1.4, -0.75};
  std::optional<Eigen::Vector2d> extra_post;
  double reacquire_speed_mps = 2.0;
  int confirm_hits = 3;
};

struct ReturnRun {
  std::vector<ScanResult> scans;
  int64_t walker_id = 0;   // the walker's track before it left the view
  int64_t walker_first_seen = 0;
  int return_scan = -1;    // index of the first scan that sees the walker again
};

FeatureReading Feature(const Eigen::Vector2d& p) {
  FeatureReading f;
  f.range_m = p.norm();
  f.bearing_rad = std::atan2(p.y(), p.x());
  f.range_var_m2 = 0.03 * 0.03;
  f.bearing_var_rad2 = 0.01 * 0.01;
  return f;
}

bool InView(const Eigen::Vector2d& p) { return std::abs(std::atan2(p.y(), p.x())) < 89 * kDegree; }

ReturnRun RunReturn(const ReturnCase& c) {
  EstimatorOptions options;
  options.field_of_view_rad = M_PI;
  options.tracks.reacquire_speed_mps = c.reacquire_speed_mps;
  options.tracks.confirm_hits = c.confirm_hits;
  Estimator estimator(options);
  std::mt19937_64 rng(5);
  const Eigen::Vector2d posts[2] = {{6.0, 1.0}, {4.0, -4.0}};
  const Eigen::Vector2d start(3.0, 1.5);
  const Eigen::Vector2d velocity(-1.0, 0.0);
  ReturnRun run;
  int last_seen_scan = -1;
  ObjectEstimate walker_track;
  for (int k = 0; k < 80; ++k) {
    const int64_t utime = 1 + k * kScan;
    OdometryReading standing;
    standing.utime = utime;
    estimator.AddOdometry(standing);
    ScanInput scan;
    scan.utime = utime;
    for (const Eigen::Vector2d& post : posts) scan.features.push_back(Feature(post));
    const Eigen::Vector2d walker = start + velocity * (static_cast<double>(k) / 8.0);
    const bool leaving = run.return_scan < 0 && InView(walker) && last_seen_scan + 1 == k;
    const bool back =
        last_seen_scan >= 0 && k >= last_seen_scan + static_cast<int>(std::lround(8 * c.unseen_s));
    if (leaving) {
      scan.features.push_back(Feature(walker));
      last_seen_scan = k;
    } else if (back) {
      if (run.return_scan < 0) run.return_scan = k;
      scan.features.push_back(Feature(c.return_point));
    }
    if (c.extra_post && k != run.return_scan) scan.features.push_back(Feature(*c.extra_post));
    run.scans.push_back(estimator.ProcessScan(scan, &rng));
    if (k == last_seen_scan) {  // the walker's track while it is in view
      for (const ObjectEstimate& o : run.scans.back().objects) {
        if ((o.position - walker).norm() < 0.3) walker_track = o;
      }
    }
    if (run.return_scan >= 0 && k >= run.return_scan + 3) break;
  }
  // When last seen, the walker was a confirmed MOVING track.
  EXPECT_EQ(walker_track.object_class, ObjectClass::kMoving);
  EXPECT_TRUE(walker_track.confirmed);
  run.walker_id = walker_track.id;
  run.walker_first_seen = walker_track.first_seen_utime;
  EXPECT_EQ(last_seen_scan, 23) << "the walker should leave the view after 2.875 s";
  EXPECT_NE(run.walker_id, 0) << "no track of the walker";
  EXPECT_GT(run.return_scan, 0) << "the walker never came back";
  return run;
}

// The objects of `result` within 0.3 m of `point`.
std::vector<ObjectEstimate> Near(const ScanResult& result, const Eigen::Vector2d& point) {
  std::vector<ObjectEstimate> near;
  for (const ObjectEstimate& o : result.objects) {
    if ((o.position - point).norm() < 0.3) near.push_back(o);
  }
  return near;
}

int TotalReacquired(const ReturnRun& run) {
  int total = 0;
  for (const ScanResult& s : run.scans) total += s.counts.reacquired;
  return total;
}

TEST(ReacquisitionTest, AWalkerBackWithinWalkingReachKeepsItsIdentityAtItsSecondMeasurement) {
  // Back 1.5 s later, 2.6 m from where it was last seen (reach 3 m), far outside the gate of
  // its track, which coasted on along -x out of view.
  ReturnCase c;
  c.return_point = Eigen::Vector2d(0.125, 1.5) + 2.6 * Eigen::Vector2d(0.5, -std::sqrt(0.75));
  const ReturnRun run = RunReturn(c);
  ASSERT_GT(run.return_scan, 0);
  const ScanResult& first = run.scans[static_cast<size_t>(run.return_scan)];
  const ScanResult& second = run.scans[static_cast<size_t>(run.return_scan + 1)];
  // First measurement: a new tentative object; the lost track is still there, not reported.
  EXPECT_EQ(first.counts.new_objects, 1);
  EXPECT_EQ(first.counts.reacquired, 0);
  for (const ObjectEstimate& o : first.objects) {
    if (o.id == run.walker_id) {
      EXPECT_FALSE(o.confirmed) << "a lost track is not reported";
    }
  }
  // Second measurement: the new object takes over the identity, first sighting and MOVING
  // label, confirmed at once; the lost track is gone (one object with that id).
  EXPECT_EQ(second.counts.reacquired, 1);
  const std::vector<ObjectEstimate> near = Near(second, c.return_point);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_EQ(near[0].id, run.walker_id);
  EXPECT_EQ(near[0].first_seen_utime, run.walker_first_seen);
  EXPECT_EQ(near[0].object_class, ObjectClass::kMoving);
  EXPECT_TRUE(near[0].confirmed);
  int with_id = 0;
  for (const ObjectEstimate& o : second.objects) with_id += o.id == run.walker_id ? 1 : 0;
  EXPECT_EQ(with_id, 1);
  EXPECT_EQ(TotalReacquired(run), 1);

  // The same run with re-acquisition off: a new identity.
  c.reacquire_speed_mps = 0.0;
  const ReturnRun off = RunReturn(c);
  ASSERT_GT(off.return_scan, 0);
  const std::vector<ObjectEstimate> near_off =
      Near(off.scans[static_cast<size_t>(off.return_scan + 1)], c.return_point);
  ASSERT_EQ(near_off.size(), 1u);
  EXPECT_NE(near_off[0].id, off.walker_id);
  EXPECT_EQ(TotalReacquired(off), 0);
}

// With confirm_hits 2 (or 1) the new object is already confirmed by its own hits when its
// second measurement comes: it must still take over the lost track's identity.
TEST(ReacquisitionTest, AlsoWhenTheNewObjectIsConfirmedByItsSecondHit) {
  ReturnCase c;
  c.return_point = Eigen::Vector2d(0.125, 1.5) + 2.6 * Eigen::Vector2d(0.5, -std::sqrt(0.75));
  for (int confirm_hits : {1, 2}) {
    c.confirm_hits = confirm_hits;
    const ReturnRun run = RunReturn(c);
    ASSERT_GT(run.return_scan, 0);
    const ScanResult& second = run.scans[static_cast<size_t>(run.return_scan + 1)];
    EXPECT_EQ(second.counts.reacquired, 1) << "confirm_hits " << confirm_hits;
    const std::vector<ObjectEstimate> near = Near(second, c.return_point);
    ASSERT_EQ(near.size(), 1u);
    EXPECT_EQ(near[0].id, run.walker_id) << "confirm_hits " << confirm_hits;
    EXPECT_EQ(near[0].object_class, ObjectClass::kMoving);
    EXPECT_EQ(TotalReacquired(run), 1);
  }
}

TEST(ReacquisitionTest, NotBeyondWalkingReach) {
  // Back 1.5 s later, 3.4 m from where it was last seen: 2.3 m/s, faster than a walk (2 m/s).
  ReturnCase c;
  c.return_point = Eigen::Vector2d(0.125, 1.5) + 3.4 * Eigen::Vector2d(0.5, -std::sqrt(0.75));
  const ReturnRun run = RunReturn(c);
  ASSERT_GT(run.return_scan, 0);
  const std::vector<ObjectEstimate> near =
      Near(run.scans[static_cast<size_t>(run.return_scan + 1)], c.return_point);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_NE(near[0].id, run.walker_id);
  EXPECT_FALSE(near[0].confirmed) << "a new object is confirmed after 3 hits";
  EXPECT_EQ(TotalReacquired(run), 0);
  // Given 0.25 s more (reach 3.5 m), the same point is within reach.
  c.unseen_s = 1.75;
  EXPECT_EQ(TotalReacquired(RunReturn(c)), 1);
}

// A post at (3, -1), STATIC long before the walker comes back (2.5 s after its last sighting:
// reach 5 m). On the return scan the post is not measured and a measurement lies `offset_m`
// behind it along the line of sight; it is measured again at the next scan, next to the post's
// own measurement. Returns how many identities were taken over.
int ReacquiredNextToAnUnmeasuredPost(double offset_m) {
  const Eigen::Vector2d post(3.0, -1.0);
  ReturnCase c;
  c.unseen_s = 2.5;
  c.extra_post = post;
  c.return_point = post + offset_m * post.normalized();
  const ReturnRun run = RunReturn(c);
  if (run.return_scan <= 0) return -1;
  const std::vector<ObjectEstimate> before =
      Near(run.scans[static_cast<size_t>(run.return_scan - 1)], post);
  EXPECT_EQ(before.size(), 1u);
  if (!before.empty()) {
    EXPECT_EQ(before[0].object_class, ObjectClass::kStatic);
  }
  // The returning measurement started a new object in both cases.
  EXPECT_EQ(run.scans[static_cast<size_t>(run.return_scan)].counts.new_objects, 1);
  return TotalReacquired(run);
}

TEST(ReacquisitionTest, NotForAMeasurementThatAnUnmeasuredLandmarkMostLikelyProduced) {
  // The post's innovation covariance is about R (range sigma 0.03 m): 0.17 m behind it is a
  // NIS of about 31, outside the new-object gate dn (20) but within 2 dn; 0.3 m is about 98.
  EXPECT_EQ(ReacquiredNextToAnUnmeasuredPost(0.17), 0)
      << "a measurement within twice the new-object gate of an unmeasured landmark carries no "
         "identity";
  EXPECT_EQ(ReacquiredNextToAnUnmeasuredPost(0.30), 1)
      << "farther from the post the same return is a re-acquisition";
}

}  // namespace
}  // namespace slammtt
