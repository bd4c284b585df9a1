// The track-management steps of a scan: hits and misses (estimator/hits_and_misses.h),
// classification (estimator/classification.h), pruning (estimator/pruning.h) and new objects
// (estimator/new_objects.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "estimator/classification.h"
#include "estimator/hits_and_misses.h"
#include "estimator/motion_classifier.h"
#include "estimator/new_objects.h"
#include "estimator/pruning.h"
#include "estimator/scan_gating.h"
#include "estimator/track_management.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::kSecond;
using testing::StepScene;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Hits and misses.

TEST(HitsAndMissesTest, AMeasuredObjectIsHitAnUnmeasuredOneMissed) {
  StepScene scene;
  scene.options.field_of_view_rad = M_PI;
  const int seen = scene.AddMover({4.0, 0.0}, 0.05, {0.0, 0.0}, 0.1);
  const int unseen = scene.AddMover({0.0, 4.0}, 0.05, {0.0, 0.0}, 0.1);  // 90 degrees: edge
  const int behind = scene.AddMover({-4.0, 0.0}, 0.05, {0.0, 0.0}, 0.1);   // out of view
  const int in_view = scene.AddMover({4.0, -2.0}, 0.05, {0.0, 0.0}, 0.1);  // in view, missed
  scene.state.object(seen).record.hits = 2;
  scene.Measure({4.02, 0.0});
  Assignment assignment(1, 4);
  assignment.Set(0, seen);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, 3 * kSecond};
  RecordHitsAndMisses(scan, {0.0}, 0.125, scene.options, scene.Predictions(), assignment,
                      &scene.state);
  const ObjectRecord& hit = scene.state.object(seen).record;
  EXPECT_EQ(hit.hits, 3);
  EXPECT_EQ(hit.last_seen_utime, 3 * kSecond);
  EXPECT_EQ(hit.last_seen_m, scene.state.position(seen));
  EXPECT_EQ(hit.unseen_observable_s, 0.0);
  EXPECT_EQ(scene.state.object(unseen).record.unseen_observable_s, 0.0) << "not surely in view";
  EXPECT_EQ(scene.state.object(behind).record.unseen_observable_s, 0.0);
  EXPECT_EQ(scene.state.object(in_view).record.unseen_observable_s, 0.125);
  EXPECT_EQ(scene.state.object(in_view).record.unseen_in_view_s, 0.125);
}

TEST(HitsAndMissesTest, AnObjectInTheShadowOfAFeatureIsNotExpectedVisible) {
  StepScene scene;
  const int hidden = scene.AddMover({8.0, 0.0}, 0.05, {0.0, 0.0}, 0.1);
  scene.Measure({4.0, 0.0});  // something in front of it
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, kSecond};
  RecordHitsAndMisses(scan, {0.5}, 0.125, scene.options, scene.Predictions(), Assignment(1, 1),
                      &scene.state);
  EXPECT_EQ(scene.state.object(hidden).record.unseen_observable_s, 0.125);
  EXPECT_EQ(scene.state.object(hidden).record.unseen_in_view_s, 0.0);
  // The static world of baseline (a) counts no misses.
  scene.options.mode = AssociationMode::kStaticNearestNeighbour;
  RecordHitsAndMisses(scan, {0.5}, 0.125, scene.options, scene.Predictions(), Assignment(1, 1),
                      &scene.state);
  EXPECT_EQ(scene.state.object(hidden).record.unseen_observable_s, 0.125);
}

// ---------------------------------------------------------------------------------------------
// Classification.

TEST(ClassificationTest, ALandmarksOwnMeasurementSpeaksForItElseTheNearestFreeOneInsideDn) {
  StepScene scene;
  const int measured = scene.AddLandmark({5.0, 0.0}, 0.05);
  const int unmeasured = scene.AddLandmark({0.0, 5.0}, 0.05);
  const int mover = scene.AddMover({-5.0, 0.0}, 0.05, {0.0, 0.0}, 0.1);
  scene.Measure({5.0, 0.02});   // 0: the landmark's own
  scene.Measure({5.0, -0.02});  // 1: also near it, unassigned
  scene.Measure({0.05, 5.2});   // 2: 20 cm from the other landmark, unassigned (NIS < dn)
  scene.Measure({0.0, 5.1});    // 3: 10 cm from it: nearer
  scene.Measure({-5.0, 0.01});  // 4: the mover's (movers are judged by their velocity)
  Assignment assignment(5, 3);
  assignment.Set(0, measured);
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  const std::vector<int> m = LandmarkMeasurements(gating.gated, scene.options, scene.state,
                                                  assignment);
  EXPECT_EQ(m[static_cast<size_t>(measured)], 0);
  EXPECT_EQ(m[static_cast<size_t>(unmeasured)], 3);
  EXPECT_EQ(m[static_cast<size_t>(mover)], -1);
}

// One scan in which the scene's landmark at (-4, 0) is measured 12 cm beside where it was
// mapped (inside its gate dn), then every object is classified; returns the scan's counts.
StepCounts ClassifyWithAMeasurementBesideTheLandmark(StepScene* scene,
                                                   const std::vector<uint8_t>& may_update,
                                                   const Assignment& assignment) {
  scene->measurements.clear();
  scene->Measure({-4.0, 0.12});
  ObservationPredictions predicted(scene->options.sensor);
  const ScanGating gating =
      GateScan(scene->measurements, predicted.At(scene->state), scene->options);
  const ScanAssociation scan{scene->measurements, may_update, 5 * kSecond};
  StepCounts counts;
  ClassifyObjects(scan, gating.gated, scene->options, scene->Predictions(), assignment,
                  &scene->state, &counts);
  return counts;
}

TEST(ClassificationTest, AFastObjectBecomesMovingAStillOneStaticAMovedLandmarkUndecided) {
  StepScene scene;
  scene.options.classifier.moving_confirm_scans = 1;
  const int fast = scene.AddMover({4.0, 2.0}, 0.05, {1.0, 0.0}, 0.05, ObjectClass::kUndecided);
  scene.state.object(fast).record.hits_with_velocity =
      scene.options.classifier.moving_evidence_min_hits;  // measured often enough
  const int still = scene.AddMover({4.0, -2.0}, 0.05, {0.0, 0.0}, 0.02, ObjectClass::kMoving);
  ObjectRecord& r = scene.state.object(still).record;
  r.still_anchor_m = scene.state.position(still);
  r.still_anchor_utime = 0;
  r.still_anchor_variance_m2 = 0.0025;
  r.last_seen_utime = 5 * kSecond;  // measured this scan, still for 5 s
  const int landmark = scene.AddLandmark({-4.0, 0.0}, 0.02);
  scene.state.object(landmark).record.num_offsets = 0;
  // Measurements 12 cm beside the landmark at every scan (inside its gate dn): it has moved.
  const std::vector<uint8_t> may_update = {1, 1, 1};
  int started = 0;
  for (int scan_index = 0; scan_index < 4 && started == 0; ++scan_index) {
    const StepCounts counts =
        ClassifyWithAMeasurementBesideTheLandmark(&scene, may_update, Assignment(1, 3));
    if (scan_index == 0) {
      EXPECT_EQ(counts.became_moving, 1);
      EXPECT_EQ(counts.became_static, 1);
      EXPECT_EQ(scene.state.object(fast).record.object_class, ObjectClass::kMoving);
      EXPECT_EQ(scene.state.object(still).record.object_class, ObjectClass::kStatic);
      EXPECT_FALSE(scene.state.object(still).has_velocity());
    }
    started += counts.started_moving;
  }
  EXPECT_EQ(started, 1);
  EXPECT_EQ(scene.state.object(landmark).record.object_class, ObjectClass::kUndecided);
  EXPECT_TRUE(scene.state.object(landmark).has_velocity());
}

// A cluster that comes and goes (a wall edge seen through dropouts, a chair leg): two
// sightings 0.5 m apart give its velocity estimate a significant 1 m/s, scan after scan while it
// coasts unseen. Two hits since it got its velocity states are no evidence of motion.
struct FlickeringCluster {
  ObjectRecord record = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  MotionClassifierOptions options;
  FlickeringCluster() {
    options.moving_evidence_min_hits = 3;  // the rule on (off by default)
    RecordHit(kSecond / 2, TrackManagementOptions(), &record);
  }
  // Judged at the scans after its second hit, unmeasured; returns the first class change.
  ClassChange JudgeCoasting(int scans) {
    for (int k = 1; k <= scans; ++k) {
      const int64_t utime = kSecond / 2 + k * kSecond / 10;
      const ClassChange change = ClassifyMover(
          Eigen::Vector2d(0.5 + 0.1 * k, 0.0), 0.01 * Eigen::Matrix2d::Identity(),
          Eigen::Vector2d(1.0, 0.0), 0.04 * Eigen::Matrix2d::Identity(), utime, options, &record);
      if (change != ClassChange::kNone) return change;
    }
    return ClassChange::kNone;
  }
};

TEST(ClassificationTest, AFlickeringClusterWithTwoHitsNeverBecomesMoving) {
  FlickeringCluster cluster;
  ASSERT_EQ(cluster.options.moving_evidence_min_hits, 3);
  ASSERT_EQ(cluster.record.hits_with_velocity, 2) << "its first measurement and one more";
  EXPECT_EQ(cluster.JudgeCoasting(20), ClassChange::kNone);
  EXPECT_EQ(cluster.record.object_class, ObjectClass::kUndecided);
  EXPECT_GE(cluster.record.moving_evidence_scans, 20) << "the velocity alone says moving";
  // A third measurement (its estimate predicted where it is) lets the evidence count.
  RecordHit(3 * kSecond, TrackManagementOptions(), &cluster.record);
  EXPECT_EQ(cluster.JudgeCoasting(1), ClassChange::kBecameMoving);
}

TEST(ClassificationTest, WithoutAMinimumOfHitsTwoSightingsMakeAMover) {
  for (int min_hits : {0, 1, 2}) {
    FlickeringCluster cluster;
    cluster.options.moving_evidence_min_hits = min_hits;
    EXPECT_EQ(cluster.JudgeCoasting(20), ClassChange::kBecameMoving) << min_hits;
    EXPECT_EQ(cluster.record.object_class, ObjectClass::kMoving);
  }
}

// The minimum for objects that are not people leaves people as they were: the same two
// sightings make a person track MOVING, and another object only after the minimum.
TEST(ClassificationTest, TheMinimumOfHitsForOtherObjectsSparesPeople) {
  FlickeringCluster person;
  person.options.moving_evidence_min_hits = 0;
  person.options.other_moving_evidence_min_hits = 8;
  person.record.kind = ObjectKind::kPerson;
  EXPECT_EQ(person.JudgeCoasting(20), ClassChange::kBecameMoving);

  FlickeringCluster other;
  other.options.moving_evidence_min_hits = 0;
  other.options.other_moving_evidence_min_hits = 8;
  ASSERT_EQ(other.record.kind, ObjectKind::kOther);
  EXPECT_EQ(other.JudgeCoasting(20), ClassChange::kNone);
  for (int k = 0; k < 5; ++k) RecordHit(3 * kSecond + k, TrackManagementOptions(), &other.record);
  ASSERT_EQ(other.record.hits_with_velocity, 7);
  EXPECT_EQ(other.JudgeCoasting(1), ClassChange::kNone) << "7 of 8";
  RecordHit(4 * kSecond, TrackManagementOptions(), &other.record);
  EXPECT_EQ(other.JudgeCoasting(1), ClassChange::kBecameMoving);
}

TEST(ClassificationTest, ALandmarkThatStartsMovingCountsItsHitsAfresh) {
  StepScene scene;
  const int landmark = scene.AddLandmark({-4.0, 0.0}, 0.02);
  ObjectRecord& r = scene.state.object(landmark).record;
  r.hits = 50;
  r.hits_with_velocity = 50;
  r.last_seen_utime = 5 * kSecond;  // its own measurement this scan (RecordHit came first)
  const std::vector<uint8_t> may_update = {1};
  int started = 0;
  for (int scan_index = 0; scan_index < 4 && started == 0; ++scan_index) {
    Assignment assignment(1, 1);
    assignment.Set(0, landmark);
    const StepCounts counts =
        ClassifyWithAMeasurementBesideTheLandmark(&scene, may_update, assignment);
    started += counts.started_moving;
  }
  ASSERT_EQ(started, 1);
  EXPECT_EQ(scene.state.object(landmark).record.hits_with_velocity, 1);
}

TEST(ClassificationTest, TheStaticWorldClassifiesNothing) {
  StepScene scene;
  scene.options.mode = AssociationMode::kStaticNearestNeighbour;
  scene.options.classifier.moving_confirm_scans = 1;
  scene.AddMover({4.0, 2.0}, 0.05, {1.0, 0.0}, 0.05, ObjectClass::kUndecided);
  const std::vector<uint8_t> may_update = {1};
  const ScanAssociation scan{scene.measurements, may_update, kSecond};
  ClassifyObjects(scan, {}, scene.options, scene.Predictions(), Assignment(0, 1), &scene.state,
                  &scene.counts);
  EXPECT_EQ(scene.counts.became_moving, 0);
  EXPECT_EQ(scene.state.object(0).record.object_class, ObjectClass::kUndecided);
}

// ---------------------------------------------------------------------------------------------
// Pruning.

TEST(PruningTest, DropsWhatShouldPruneSaysAndTheTakenOverTracksWithoutCountingThem) {
  StepScene scene;
  const int stale = scene.AddMover({4.0, 0.0}, 0.05, {0.0, 0.0}, 0.1, ObjectClass::kUndecided);
  scene.state.object(stale).record.confirmed = false;  // tentative, unseen for 2 s
  const int fresh = scene.AddMover({0.0, 4.0}, 0.05, {0.0, 0.0}, 0.1);
  scene.state.object(fresh).record.last_seen_utime = 2 * kSecond;
  const int taken_over = scene.AddMover({-4.0, 0.0}, 0.05, {0.0, 0.0}, 0.1);
  scene.state.object(taken_over).record.last_seen_utime = 2 * kSecond;
  const int64_t fresh_id = scene.state.object(fresh).record.id;
  const std::vector<ObjectPrediction> predictions = scene.Predictions();
  EXPECT_EQ(ObjectsToPrune(2 * kSecond, scene.options, predictions, scene.state,
                           Assignment(0, 3)),
            std::vector<int>{stale});
  PruneObjects(2 * kSecond, {taken_over}, scene.options, predictions, Assignment(0, 3),
               &scene.state, &scene.counts);
  EXPECT_EQ(scene.counts.pruned, 1);
  ASSERT_EQ(scene.state.num_objects(), 1);
  EXPECT_EQ(scene.state.object(0).record.id, fresh_id);
  // Baseline (a) prunes nothing.
  scene.options.mode = AssociationMode::kStaticNearestNeighbour;
  scene.state.object(0).record.confirmed = false;
  EXPECT_TRUE(ObjectsToPrune(60 * kSecond, scene.options, scene.Predictions(), scene.state,
                             Assignment(0, 1))
                  .empty());
}

// ---------------------------------------------------------------------------------------------
// New objects.

TEST(NewObjectsTest, FreeMeasurementsOutsideDnOfEveryObjectStartUndecidedTentativeObjects) {
  StepScene scene;
  scene.AddLandmark({5.0, 0.0}, 0.05);
  scene.Measure({5.02, 0.0});  // 0: near the landmark (NIS < dn): no new object
  scene.Measure({0.0, 4.0});   // 1: new
  scene.Measure({0.0, -4.0});  // 2: new, the continuation of lost track 42
  scene.Measure({3.0, 3.0});   // 3: new, a person: no landmark, so no first sighting
  scene.measurements[3].person = true;
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  ASSERT_LT(gating.nearest_nis[0], scene.options.new_object_gate_dn_chi2);
  const std::vector<uint8_t> may_update = {1};
  const ScanAssociation scan{scene.measurements, may_update, 4 * kSecond};
  int64_t next_id = 10;
  const std::vector<StaticObservation> first_sightings =
      AddNewObjects(scan, gating.nearest_nis, {0, 0, 42, 0}, scene.options, Assignment(4, 1),
                    &next_id, &scene.state, &scene.counts);
  EXPECT_EQ(scene.counts.new_objects, 3);
  EXPECT_EQ(next_id, 13);
  ASSERT_EQ(scene.state.num_objects(), 4);
  // The smoother gets the measurements that started the two objects that may be landmarks,
  // tentative (undecided objects), under the new objects' ids.
  ASSERT_EQ(first_sightings.size(), 2u);
  for (int k : {1, 2}) {
    const StaticObservation& o = first_sightings[static_cast<size_t>(k - 1)];
    EXPECT_EQ(o.landmark_id, 9 + k);
    EXPECT_EQ(o.range_bearing, scene.measurements[static_cast<size_t>(k)].range_bearing);
    EXPECT_EQ(o.covariance, scene.measurements[static_cast<size_t>(k)].covariance);
    EXPECT_TRUE(o.tentative);
  }
  for (int k : {1, 2}) {
    const StateObject& o = scene.state.object(k);
    EXPECT_EQ(o.record.id, 9 + k);
    EXPECT_EQ(o.record.object_class, ObjectClass::kUndecided);
    EXPECT_FALSE(o.record.confirmed);
    EXPECT_EQ(o.record.first_seen_utime, 4 * kSecond);
    ASSERT_TRUE(o.has_velocity());
    EXPECT_EQ(scene.state.velocity(k), Eigen::Vector2d::Zero());
    const double sigma = scene.options.new_object_velocity_sigma_mps;
    EXPECT_EQ(scene.state.covariance()(o.velocity_index, o.velocity_index), sigma * sigma);
  }
  EXPECT_NEAR((scene.state.position(1) - Eigen::Vector2d(0.0, 4.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(scene.state.object(1).record.continues_id, 0);
  EXPECT_EQ(scene.state.object(2).record.continues_id, 42);
}

// Two things side by side: an object that took its own measurement does not keep a second
// measurement inside its gate dn from starting an object (new_object_gate_skips_claimed_objects);
// one that took none still does, and so does a MOVING one (most likely the same walker). The
// UNDECIDED object beside such a birth forgets its moving evidence.
TEST(NewObjectsTest, AClaimedObjectDoesNotBlockABirthBesideIt) {
  StepScene scene;
  const int undecided = scene.AddMover({8.0, 0.0}, 0.05, {0.0, 0.0}, 0.5, ObjectClass::kUndecided);
  const int unclaimed = scene.AddLandmark({0.0, 8.0}, 0.05);
  const int moving = scene.AddMover({8.0, -3.0}, 0.05, {0.0, 0.0}, 0.5, ObjectClass::kMoving);
  scene.state.object(undecided).record.moving_evidence_scans = 1;
  scene.state.object(moving).record.moving_evidence_scans = 3;
  scene.Measure({8.0, 0.0});    // 0: the undecided object's own
  scene.Measure({8.2, 0.0});    // 1: beside it
  scene.Measure({0.0, 8.2});    // 2: beside the landmark, which took nothing
  scene.Measure({8.0, -3.0});   // 3: the moving object's own
  scene.Measure({8.2, -3.0});   // 4: beside it
  scene.Measure({4.0, 4.0});    // 5: far from everything
  const double dn = scene.options.new_object_gate_dn_chi2;
  ASSERT_LT(scene.Nis(1, undecided), dn);
  ASSERT_LT(scene.Nis(2, unclaimed), dn);
  ASSERT_LT(scene.Nis(4, moving), dn);
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  Assignment assignment(6, 3);
  assignment.Set(0, undecided);
  assignment.Set(3, moving);

  scene.options.new_object_gate_skips_claimed_objects = false;
  const std::vector<double> blocked = NearestNisForBirths(scene.measurements, gating, assignment, scene.state, scene.options);
  EXPECT_EQ(blocked, gating.nearest_nis);
  EXPECT_TRUE(ClaimedObjectsBesideBirths(gating, blocked, assignment, dn).empty());

  scene.options.new_object_gate_skips_claimed_objects = true;
  scene.options.new_object_beside_claimed_min_separation_m = 0.1;  // the points are 0.2 m apart
  const std::vector<double> births = NearestNisForBirths(scene.measurements, gating, assignment, scene.state, scene.options);
  ASSERT_EQ(births.size(), 6u);
  EXPECT_GE(births[1], dn);
  EXPECT_EQ(births[2], gating.nearest_nis[2]);
  EXPECT_LT(births[2], dn);
  EXPECT_EQ(births[4], gating.nearest_nis[4]);
  EXPECT_LT(births[4], dn);
  EXPECT_EQ(births[5], gating.nearest_nis[5]);
  const std::vector<int> beside = ClaimedObjectsBesideBirths(gating, births, assignment, dn);
  EXPECT_EQ(beside, (std::vector<int>{undecided}));
  const std::vector<uint8_t> all_update = scene.AllMayUpdate();
  const ScanAssociation this_scan{scene.measurements, all_update, 4 * kSecond};
  EXPECT_EQ(RestartObjectsBesideBirths(beside, this_scan, assignment, scene.options, &scene.state),
            1);
  EXPECT_EQ(scene.state.object(undecided).record.moving_evidence_scans, 0);
  // Only an UNDECIDED object is restarted.
  EXPECT_EQ(RestartObjectsBesideBirths({moving}, this_scan, assignment, scene.options,
                                       &scene.state),
            0);
  EXPECT_EQ(scene.state.object(moving).record.moving_evidence_scans, 3);
  // A person still blocks the point beside it (its other leg).
  scene.state.object(undecided).record.kind = ObjectKind::kPerson;
  EXPECT_LT(NearestNisForBirths(scene.measurements, gating, assignment, scene.state,
                                scene.options)[1],
            dn);
  scene.state.object(undecided).record.kind = ObjectKind::kOther;
  // Nor does a point nearer to the object's own than the separation.
  scene.options.new_object_beside_claimed_min_separation_m = 0.3;
  EXPECT_LT(NearestNisForBirths(scene.measurements, gating, assignment, scene.state,
                                scene.options)[1],
            dn);
  scene.options.new_object_beside_claimed_min_separation_m = 0.1;

  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, 4 * kSecond};
  int64_t next_id = 10;
  AddNewObjects(scan, births, std::vector<int64_t>(6, 0), scene.options, assignment, &next_id,
                &scene.state, &scene.counts);
  EXPECT_EQ(scene.counts.new_objects, 2);  // measurements 1 and 5
}

// Two posts 3 m apart at 30 m, at the edge of the range: an UNDECIDED object born on one took the
// other's measurements while the first was out of range, so its estimate stands near the second
// post with a covariance grown small on those measurements and a velocity from the walk. Once a
// new object is born on the second post, the first object starts again from its own measurement
// (new_object_beside_claimed_restarts_state) as a new object would be: kept, it would walk back
// to its post as a velocity and become a false MOVING track (s1-crossing seed 3).
TEST(NewObjectsTest, AnObjectBesideABirthStartsAgainFromItsOwnMeasurement) {
  StepScene scene;
  scene.state = SlamState(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0.01, 1e-4).asDiagonal());
  const Eigen::Vector2d own_post(30.0, 0.0);
  const Eigen::Vector2d other_post(30.0, 3.0);
  // A landmark seen before, correlated with the robot.
  Eigen::Matrix<double, 2, 3> g;
  g << 1.0, 0.0, 0.0, 0.0, 1.0, 10.0;
  ObjectRecord landmark_record;
  landmark_record.id = 1;
  landmark_record.object_class = ObjectClass::kStatic;
  const int landmark = scene.state.AddObject({10.0, 0.0}, g, 0.01 * Eigen::Matrix2d::Identity(),
                                             landmark_record);
  const int dragged = scene.AddMover({30.0, 2.4}, 0.3, {0.2, 0.9}, 0.4, ObjectClass::kUndecided);
  scene.state.object(dragged).record.moving_evidence_scans = 1;
  scene.state.object(dragged).record.hits_with_velocity = 6;
  const int own = scene.Measure(own_post, 0.03, 0.035);     // 2 degrees of bearing noise
  scene.Measure(other_post, 0.03, 0.035);                   // starts an object beside it
  Assignment assignment(2, scene.state.num_objects());
  assignment.Set(own, dragged);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, 4 * kSecond};
  const SlamState kept_state = scene.state;

  // Off: only the moving evidence restarts, the estimate stays between the posts.
  scene.options.new_object_beside_claimed_restarts_state = false;
  EXPECT_EQ(RestartObjectsBesideBirths({dragged}, scan, assignment, scene.options, &scene.state),
            1);
  EXPECT_EQ(scene.state.object(dragged).record.moving_evidence_scans, 0);
  EXPECT_EQ(scene.state.position(dragged), kept_state.position(dragged));
  EXPECT_EQ(scene.state.velocity(dragged), kept_state.velocity(dragged));

  // On: the object is where its own measurement puts it, with a new object's uncertainty.
  scene.state = kept_state;
  scene.options.new_object_beside_claimed_restarts_state = true;
  EXPECT_EQ(RestartObjectsBesideBirths({dragged}, scan, assignment, scene.options, &scene.state),
            1);
  const ObjectRecord& record = scene.state.object(dragged).record;
  EXPECT_EQ(record.moving_evidence_scans, 0);
  EXPECT_EQ(record.hits_with_velocity, 1);
  EXPECT_EQ(record.id, kept_state.object(dragged).record.id);
  EXPECT_TRUE(scene.state.position(dragged).isApprox(own_post, 1e-9));
  EXPECT_EQ(scene.state.velocity(dragged), Eigen::Vector2d::Zero());
  // The same state as the object AddNewObjects starts from that measurement.
  SlamState fresh = kept_state;
  const std::vector<double> births = {kInfinity, 0.0};
  Assignment none(2, fresh.num_objects());
  int64_t next_id = 50;
  StepCounts counts;
  AddNewObjects(scan, births, {0, 0}, scene.options, none, &next_id, &fresh, &counts);
  ASSERT_EQ(counts.new_objects, 1);
  const int born = fresh.num_objects() - 1;
  EXPECT_TRUE(fresh.position(born).isApprox(scene.state.position(dragged)));
  EXPECT_TRUE(fresh.ObjectCovariance(born).isApprox(scene.state.ObjectCovariance(dragged)));
  const int p_fresh = fresh.object(born).position_index;
  const int p_dragged = scene.state.object(dragged).position_index;
  const int p_landmark = scene.state.object(landmark).position_index;
  EXPECT_TRUE((fresh.covariance().block<2, 2>(p_fresh, p_landmark).isApprox(
      scene.state.covariance().block<2, 2>(p_dragged, p_landmark))));
  EXPECT_TRUE((fresh.covariance().block<2, 3>(p_fresh, 0).isApprox(
      scene.state.covariance().block<2, 3>(p_dragged, 0))));
  // A wider position uncertainty than the dragged estimate had: the next measurements of its
  // post move the estimate, not the velocity.
  const double restarted_variance =
      scene.state.ObjectCovariance(dragged).topLeftCorner<2, 2>().trace();
  const double dragged_variance = kept_state.ObjectCovariance(dragged).topLeftCorner<2, 2>().trace();
  EXPECT_GT(restarted_variance, dragged_variance);
}

TEST(NewObjectsTest, TheCapRefusesAndTheStaticWorldMapsConfirmedLandmarks) {
  StepScene scene;
  scene.options.mode = AssociationMode::kStaticNearestNeighbour;
  scene.options.max_objects = 1;
  scene.Measure({0.0, 4.0});
  scene.Measure({0.0, -4.0});
  const std::vector<uint8_t> may_update;
  const ScanAssociation scan{scene.measurements, may_update, kSecond};
  int64_t next_id = 1;
  const std::vector<StaticObservation> first_sightings =
      AddNewObjects(scan, {kInfinity, kInfinity}, {0, 0}, scene.options, Assignment(2, 0),
                    &next_id, &scene.state, &scene.counts);
  EXPECT_EQ(scene.counts.new_objects, 1);
  // A landmark from its first sighting: the smoother's observation is not tentative.
  ASSERT_EQ(first_sightings.size(), 1u);
  EXPECT_EQ(first_sightings[0].landmark_id, 1);
  EXPECT_FALSE(first_sightings[0].tentative);
  EXPECT_EQ(scene.counts.objects_refused, 1);
  ASSERT_EQ(scene.state.num_objects(), 1);
  EXPECT_EQ(scene.state.object(0).record.object_class, ObjectClass::kStatic);
  EXPECT_TRUE(scene.state.object(0).record.confirmed);
  EXPECT_FALSE(scene.state.object(0).has_velocity());
}

// Two person features 0.3 m apart (a person's legs split into two people) start one track; a
// third 0.3 m from an existing person track starts none; a point feature as near starts its
// object as before, and so does everything with people_min_separation_m 0.
TEST(NewObjectsTest, NoPersonTrackIsBornCloserThanTheMinimumSeparationToAnother) {
  for (const double min_separation_m : {0.4, 0.0}) {
    StepScene scene;
    scene.options.people.min_separation_m = min_separation_m;
    const int standing = scene.AddLandmark({0.0, -4.0}, 0.01);
    scene.state.object(standing).record.kind = ObjectKind::kPerson;
    scene.Measure({3.0, 0.0});    // 0: a person
    scene.Measure({3.0, 0.3});    // 1: a second person 0.3 m from the first
    scene.Measure({0.3, -4.0});   // 2: a person 0.3 m from the standing person's track
    scene.Measure({3.0, -0.3});   // 3: a point feature 0.3 m from the first person
    for (int i : {0, 1, 2}) scene.measurements[static_cast<size_t>(i)].person = true;
    ObservationPredictions predicted(scene.options.sensor);
    const ScanGating gating =
        GateScan(scene.measurements, predicted.At(scene.state), scene.options);
    ASSERT_GE(gating.nearest_nis[2], scene.options.new_object_gate_dn_chi2)
        << "outside gate dn of the standing track: a birth without the rule";
    const std::vector<uint8_t> may_update = {1};
    const ScanAssociation scan{scene.measurements, may_update, kSecond};
    int64_t next_id = 10;
    AddNewObjects(scan, gating.nearest_nis, {0, 0, 0, 0}, scene.options, Assignment(4, 1),
                  &next_id, &scene.state, &scene.counts);
    if (min_separation_m > 0.0) {
      EXPECT_EQ(scene.counts.new_objects, 2);
      EXPECT_EQ(scene.counts.person_births_joined, 2);
      ASSERT_EQ(scene.state.num_objects(), 3);
      EXPECT_EQ(scene.state.object(1).record.kind, ObjectKind::kPerson);
      EXPECT_NEAR((scene.state.position(1) - Eigen::Vector2d(3.0, 0.0)).norm(), 0.0, 1e-9);
      EXPECT_EQ(scene.state.object(2).record.kind, ObjectKind::kOther);
    } else {
      EXPECT_EQ(scene.counts.new_objects, 4);
      EXPECT_EQ(scene.counts.person_births_joined, 0);
    }
  }
}

}  // namespace
}  // namespace slammtt
