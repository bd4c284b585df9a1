// People and other movers (estimator/people.h) and the reporting rules of track management
// (estimator/track_management.h): the kind of an object, the plausible-speed gate, M-of-N
// confirmation and which tracks are reported.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/people.h"
#include "estimator/track_management.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::kSecond;
using testing::StepScene;

TEST(PeopleTest, AnObjectIsAPersonWhileMostOfItsMeasurementsWerePersonFeatures) {
  ObjectRecord record = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  record.person_hits = 1;  // first seen as a person feature
  EXPECT_EQ(KindOfRecord(record), ObjectKind::kPerson);
  record.hits = 2;  // then a point feature (legs not paired in that scan)
  RecordMeasurementKind(false, &record);
  EXPECT_EQ(record.kind, ObjectKind::kOther) << "1 of 2: not more than half";
  record.hits = 3;
  RecordMeasurementKind(true, &record);
  EXPECT_EQ(record.kind, ObjectKind::kPerson);  // 2 of 3
  ObjectRecord post = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  for (int k = 0; k < 10; ++k) {
    ++post.hits;
    RecordMeasurementKind(false, &post);
  }
  EXPECT_EQ(post.kind, ObjectKind::kOther);
}

TEST(PeopleTest, VelocitiesAreLimitedToWhatTheirKindCanReach) {
  StepScene scene;
  const int walker = scene.AddMover({4.0, 0.0}, 0.1, {1.4, 0.0}, 0.2);
  const int runner = scene.AddMover({4.0, 1.0}, 0.1, {3.0, 4.0}, 0.2);  // 5 m/s
  const int cart = scene.AddMover({4.0, 2.0}, 0.1, {3.0, 4.0}, 0.2);    // 5 m/s, not a person
  const int rocket = scene.AddMover({4.0, 3.0}, 0.1, {0.0, -20.0}, 0.2);
  scene.state.object(walker).record.kind = ObjectKind::kPerson;
  scene.state.object(runner).record.kind = ObjectKind::kPerson;
  const Eigen::MatrixXd covariance_before = scene.state.covariance();
  const PeopleOptions options;
  EXPECT_EQ(LimitSpeedsToTheirKind(options, &scene.state), 2);
  EXPECT_EQ(scene.state.velocity(walker), Eigen::Vector2d(1.4, 0.0));
  EXPECT_NEAR(scene.state.velocity(runner)(0), 3.0 * 3.0 / 5.0, 1e-12);  // direction kept
  EXPECT_NEAR(scene.state.velocity(runner)(1), 3.0 * 4.0 / 5.0, 1e-12);
  EXPECT_EQ(scene.state.velocity(cart), Eigen::Vector2d(3.0, 4.0));
  EXPECT_NEAR(scene.state.velocity(rocket)(1), -12.5, 1e-12);
  EXPECT_EQ(scene.state.covariance(), covariance_before);  // the mean only
  PeopleOptions off;
  off.max_speed_mps = 0.0;
  off.other_max_speed_mps = 0.0;
  scene.state.mean().segment<2>(scene.state.object(runner).velocity_index) << 9.0, 0.0;
  EXPECT_EQ(LimitSpeedsToTheirKind(off, &scene.state), 0);
}

// A person stood at (4, 0) (a STATIC track of kind PERSON) and walked off: the scan measured a
// confirmed MOVING person track 0.3 m from it and not the standing track, which goes. A
// standing track that was measured, one farther than taken_over_within_m, one beside a
// tentative or unmeasured walker or beside a walker born long before the standing track's last
// measurement, and everything with the option 0, stay.
TEST(PeopleTest, AStandingPersonWhoWalksOffLeavesNoStaticTrackBehind) {
  StepScene scene;
  // Standing tracks last measured at 5 s; walkers born at 5.2 s unless said otherwise.
  const auto standing_person = [&](const Eigen::Vector2d& position) {
    const int k = scene.AddLandmark(position, 0.05);
    scene.state.object(k).record.kind = ObjectKind::kPerson;
    scene.state.object(k).record.last_seen_utime = 5 * kSecond;
    return k;
  };
  const auto walker = [&](const Eigen::Vector2d& position,
                          int64_t born_utime = 52 * kSecond / 10) {
    const int k = scene.AddMover(position, 0.05, {1.0, 0.0}, 0.1);
    scene.state.object(k).record.kind = ObjectKind::kPerson;
    scene.state.object(k).record.first_seen_utime = born_utime;
    return k;
  };
  const int left_behind = standing_person({4.0, 0.0});
  const int walked_off = walker({4.3, 0.0});
  const int still_seen = standing_person({0.0, 4.0});
  walker({0.3, 4.0});
  const int far = standing_person({-4.0, 0.0});
  walker({-3.0, 0.0});
  const int beside_tentative = standing_person({0.0, -4.0});
  const int tentative = walker({0.3, -4.0});
  scene.state.object(tentative).record.confirmed = false;
  const int beside_unmeasured = standing_person({6.0, 6.0});
  const int unmeasured = walker({6.3, 6.0});
  // An old walker (born 1.5 s before the standing track's last measurement) passing by.
  const int beside_old_walker = standing_person({-6.0, 6.0});
  walker({-6.3, 6.0}, 35 * kSecond / 10);
  const int post = scene.AddLandmark({4.0, 0.2}, 0.05);  // not a person
  std::vector<uint8_t> measured(static_cast<size_t>(scene.state.num_objects()), 1);
  for (int k : {left_behind, far, beside_tentative, beside_unmeasured, unmeasured,
                beside_old_walker, post}) {
    measured[static_cast<size_t>(k)] = 0;
  }
  ASSERT_EQ(measured[static_cast<size_t>(still_seen)], 1);
  PeopleOptions options;
  ASSERT_EQ(options.taken_over_within_m, 0.5);  // on by default
  EXPECT_EQ(PersonTracksTakenOver(measured, options, scene.state), std::vector<int>{left_behind});
  measured[static_cast<size_t>(walked_off)] = 0;
  EXPECT_TRUE(PersonTracksTakenOver(measured, options, scene.state).empty());
  measured[static_cast<size_t>(walked_off)] = 1;
  options.taken_over_within_m = 0.0;  // off
  EXPECT_TRUE(PersonTracksTakenOver(measured, options, scene.state).empty());
}

// One person paces between two person tracks 0.6 m apart, each taking the measurements near it:
// over the last 10 scans they were never measured together and the measurements went from one
// to the other and back; this scan measured `pacing_b`, so `pacing_a` goes. Two people side by
// side (measured together in some scan), a pair whose measurements moved from one to the other
// only once (one hid the other), a pair farther apart than measured_in_turn_within_m, a pair
// of which one is no person, a track younger than the window, and everything with the option
// 0, stay.
TEST(PeopleTest, TwoPersonTracksMeasuredInTurnAreOnePerson) {
  StepScene scene;
  const auto person = [&](const Eigen::Vector2d& position, uint32_t recent_hits) {
    const int k = scene.AddLandmark(position, 0.05);
    ObjectRecord& r = scene.state.object(k).record;
    r.kind = ObjectKind::kPerson;
    r.recent_scans = 0xFFFFu;
    r.recent_hits = recent_hits;
    return k;
  };
  // Bit 0 is this scan. Measured in turn: b a a b b . a . b b (newest first).
  const int pacing_a = person({4.0, 0.0}, 0b0001000110u);
  const int pacing_b = person({4.6, 0.0}, 0b1100100001u);
  // Side by side: measured together in scan 2.
  const int side_a = person({0.0, 4.0}, 0b0000010110u);
  person({0.6, 4.0}, 0b1100100101u);
  // One hid the other from scan 5 on: from one track to the other once.
  const int hidden = person({0.0, -4.0}, 0b1111000000u);
  person({0.6, -4.0}, 0b0000011111u);
  // Farther apart than 1 m.
  const int far = person({-4.0, 0.0}, 0b0001000110u);
  person({-2.8, 0.0}, 0b1100100001u);
  // Not a person.
  const int post = scene.AddLandmark({6.0, 6.0}, 0.05);
  scene.state.object(post).record.recent_scans = 0xFFFFu;
  scene.state.object(post).record.recent_hits = 0b0001000110u;
  person({6.6, 6.0}, 0b1100100001u);
  // Younger than the window.
  const int young = person({-6.0, 6.0}, 0b0001000110u);
  scene.state.object(young).record.recent_scans = 0x1FFu;
  person({-6.6, 6.0}, 0b1100100001u);
  std::vector<uint8_t> measured(static_cast<size_t>(scene.state.num_objects()), 0);
  for (int k = 0; k < scene.state.num_objects(); ++k) {
    measured[static_cast<size_t>(k)] = scene.state.object(k).record.recent_hits & 1u;
  }
  ASSERT_EQ(measured[static_cast<size_t>(pacing_b)], 1);
  for (int k : {pacing_a, side_a, hidden, far, post, young}) {
    ASSERT_EQ(measured[static_cast<size_t>(k)], 0);
  }
  PeopleOptions options;
  ASSERT_EQ(options.measured_in_turn_within_m, 1.0);  // on by default
  ASSERT_EQ(options.measured_in_turn_window_scans, 10);
  EXPECT_EQ(PersonTracksMeasuredInTurn(measured, options, scene.state),
            std::vector<int>{pacing_a});
  options.measured_in_turn_within_m = 0.0;  // off
  EXPECT_TRUE(PersonTracksMeasuredInTurn(measured, options, scene.state).empty());
}

// A person track born of two legs paired with confidence 0.9 at 5 s is reported in that scan
// (while tentative), not in the next one unless confirmation says so; one born of a weaker pair,
// of one leg (confidence 0), of another kind, or with the option 0, is not reported at birth.
TEST(PeopleTest, ATwoLegPersonIsReportedInTheScanItIsBornIn) {
  PeopleOptions options;
  ASSERT_GT(options.report_pair_births_confidence, 0.0);  // on by default
  options.report_pair_births_confidence = 0.85;
  ObjectRecord born = NewObjectRecord(1, 5 * kSecond, ObjectClass::kUndecided);
  born.person_hits = 1;
  born.kind = KindOfRecord(born);
  born.birth_pair_confidence = 0.9;
  EXPECT_TRUE(ReportedAtBirth(born, 5 * kSecond, options));
  // The next scan, measured again or not: confirmation decides (track_management.h).
  EXPECT_FALSE(ReportedAtBirth(born, 52 * kSecond / 10, options));
  ObjectRecord seen_again = born;
  seen_again.last_seen_utime = 52 * kSecond / 10;
  EXPECT_FALSE(ReportedAtBirth(seen_again, 52 * kSecond / 10, options));
  ObjectRecord weak = born;
  weak.birth_pair_confidence = 0.8;
  EXPECT_FALSE(ReportedAtBirth(weak, 5 * kSecond, options));
  ObjectRecord one_leg = born;
  one_leg.birth_pair_confidence = 0.0;
  EXPECT_FALSE(ReportedAtBirth(one_leg, 5 * kSecond, options));
  ObjectRecord other = born;
  other.kind = ObjectKind::kOther;
  EXPECT_FALSE(ReportedAtBirth(other, 5 * kSecond, options));
  options.report_pair_births_confidence = 0.0;
  EXPECT_FALSE(ReportedAtBirth(born, 5 * kSecond, options));
}

// ShowsAPerson, far away: a person track 7 m from the robot is reported from its 6th hit on
// (people_report_far_m 6, people_report_far_min_hits 6, the defaults), one 5 m away from its
// confirmation; a track of kind other is not held back, and report_far_m 0 turns it off.
TEST(PeopleTest, AFarPersonTrackIsReportedOnlyOnceItWasMeasuredInEnoughScans) {
  PeopleOptions options;
  ASSERT_EQ(options.report_far_m, 6.0);  // on by default
  ASSERT_EQ(options.report_far_min_hits, 6);
  ObjectRecord person = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  person.hits = 5;
  person.person_hits = 5;
  person.kind = KindOfRecord(person);
  EXPECT_FALSE(ShowsAPerson(person, 7.0, options));
  EXPECT_TRUE(ShowsAPerson(person, 5.0, options));
  ObjectRecord sixth = person;
  sixth.hits = 6;
  sixth.person_hits = 6;
  EXPECT_TRUE(ShowsAPerson(sixth, 7.0, options));
  ObjectRecord other = person;
  other.person_hits = 0;
  other.kind = KindOfRecord(other);
  EXPECT_TRUE(ShowsAPerson(other, 7.0, options));
  options.report_far_m = 0.0;
  EXPECT_TRUE(ShowsAPerson(person, 7.0, options));
}

// ShowsAPerson: with both rules off every track is shown; a person track needs
// report_min_pair_hits scans of two legs paired and, unless MOVING, report_min_person_share of
// its hits as person features; a track of kind other is never held back by them.
TEST(PeopleTest, APersonTrackIsShownOnceItShowedTheEvidenceAskedFor) {
  PeopleOptions options;
  ASSERT_EQ(options.report_min_pair_hits, 0);  // both off by default (2 m away: near)
  ASSERT_EQ(options.report_min_person_share, 0.0);
  ObjectRecord one_leg = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  one_leg.hits = 4;
  one_leg.person_hits = 3;  // three one-leg person features and a point feature
  one_leg.kind = KindOfRecord(one_leg);
  ASSERT_EQ(one_leg.kind, ObjectKind::kPerson);
  EXPECT_TRUE(ShowsAPerson(one_leg, 2.0, options));
  options.report_min_pair_hits = 1;
  EXPECT_FALSE(ShowsAPerson(one_leg, 2.0, options));
  ObjectRecord paired = one_leg;
  paired.pair_hits = 1;
  EXPECT_TRUE(ShowsAPerson(paired, 2.0, options));
  options.report_min_pair_hits = 2;
  EXPECT_FALSE(ShowsAPerson(paired, 2.0, options));
  options.report_min_pair_hits = 0;
  options.report_min_person_share = 0.75;  // 3 of 4: shown; 3 of 5 would not make a person
  EXPECT_TRUE(ShowsAPerson(one_leg, 2.0, options));
  options.report_min_person_share = 0.8;
  EXPECT_FALSE(ShowsAPerson(one_leg, 2.0, options));
  ObjectRecord walker = one_leg;  // its motion shows it: the share is not asked of it
  walker.object_class = ObjectClass::kMoving;
  EXPECT_TRUE(ShowsAPerson(walker, 2.0, options));
  ObjectRecord post = NewObjectRecord(2, 0, ObjectClass::kStatic);
  options.report_min_pair_hits = 3;
  EXPECT_TRUE(ShowsAPerson(post, 2.0, options));
}

// A birth 0.8 m from a person track (or a MOVING track of any kind) is beside it (clearance
// 1 m); one 1.2 m away, or beside a static landmark that is not a person, is not.
TEST(PeopleTest, ABirthBesideAPersonOrAMoverIsNotClear) {
  StepScene scene;
  const int person = scene.AddLandmark({4.0, 0.0}, 0.05);
  scene.state.object(person).record.kind = ObjectKind::kPerson;
  scene.AddMover({0.0, 4.0}, 0.05, {1.0, 0.0}, 0.1);
  scene.AddLandmark({-4.0, 0.0}, 0.05);  // a post
  PeopleOptions options;
  options.report_pair_births_clear_m = 1.0;
  EXPECT_TRUE(BesideAPersonOrMover({4.8, 0.0}, options, scene.state));
  EXPECT_FALSE(BesideAPersonOrMover({5.2, 0.0}, options, scene.state));
  EXPECT_TRUE(BesideAPersonOrMover({0.0, 4.8}, options, scene.state));
  EXPECT_FALSE(BesideAPersonOrMover({-4.8, 0.0}, options, scene.state));
  options.report_pair_births_clear_m = 0.0;
  EXPECT_FALSE(BesideAPersonOrMover({4.8, 0.0}, options, scene.state));
}

// Confirmation by M of N (3 of the last 5 scans): scans hit (H) and missed (M) in the order
// H M M H M H: 3 hits in all, but only 2 in the last 5, so not confirmed (the rule before, 3
// hits at any time, confirms it); one more hit makes 3 of the last 5.
TEST(TrackManagementTest, BirthNeedsMOfTheLastNScans) {
  TrackManagementOptions options;
  ASSERT_EQ(options.confirm_hits, 3);
  ASSERT_EQ(options.confirm_window_scans, 5);
  ObjectRecord record = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  const bool hit[] = {false, false, true, false, true};
  int64_t utime = 0;
  for (bool h : hit) {
    utime += kSecond / 10;
    if (h) {
      RecordHit(utime, options, &record);
    } else {
      RecordMiss(0.1, true, true, &record);
    }
  }
  EXPECT_EQ(record.hits, 3);
  EXPECT_FALSE(record.confirmed);
  ObjectRecord before = record;
  TrackManagementOptions any_time = options;
  any_time.confirm_window_scans = 0;
  RecordHit(utime, any_time, &before);
  EXPECT_TRUE(before.confirmed) << "4 hits at any time";
  RecordHit(utime + kSecond / 10, options, &record);
  EXPECT_TRUE(record.confirmed);
  // A stray cluster seen at every third scan (H M M H M M H ...) never has 3 of the last 5,
  // however many hits it gathers.
  ObjectRecord stray = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  for (int k = 1; k <= 12; ++k) {
    if (k % 3 == 0) {
      RecordHit(k * kSecond / 10, options, &stray);
    } else {
      RecordMiss(0.1, true, true, &stray);
    }
  }
  EXPECT_EQ(stray.hits, 5);
  EXPECT_FALSE(stray.confirmed);
}

TEST(TrackManagementTest, OnlyRecentlyMeasuredTracksAreReported) {
  TrackManagementOptions options;
  ObjectRecord mover = NewObjectRecord(1, 0, ObjectClass::kMoving);
  mover.confirmed = true;
  mover.recent_hits = 0x1fu;  // measured in each of its last 5 scans
  mover.last_seen_utime = 10 * kSecond;
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond, options));
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond + kSecond / 2, options));  // 0.5 s
  EXPECT_FALSE(ReportedTrack(mover, true, 10 * kSecond + kSecond * 6 / 10, options));
  options.report_measured_within_s = 1.0;
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond + kSecond * 6 / 10, options));
  options = TrackManagementOptions();
  // A landmark is the map: reported while confirmed, however long unseen; a standing person
  // (STATIC, kind PERSON) is a track like any other.
  ObjectRecord landmark = NewObjectRecord(2, 0, ObjectClass::kStatic);
  landmark.confirmed = true;
  EXPECT_TRUE(ReportedTrack(landmark, false, 60 * kSecond, options));
  landmark.kind = ObjectKind::kPerson;
  EXPECT_FALSE(ReportedTrack(landmark, false, 60 * kSecond, options));
  ObjectRecord tentative = NewObjectRecord(3, 0, ObjectClass::kUndecided);
  EXPECT_FALSE(ReportedTrack(tentative, true, 0, options));
}

// A mover that is no person is reported while it missed at most 1 of its last 5 scans where it
// should have been seen; a MOVING person while measured in 3 of its last 5 scans, occluded or
// not; a standing person while measured within 0.5 s whatever its scans before.
TEST(TrackManagementTest, AMoverIsReportedWhileMeasuredInMOfItsLastNScans) {
  TrackManagementOptions options;
  ObjectRecord mover = NewObjectRecord(1, 0, ObjectClass::kMoving);
  mover.confirmed = true;
  mover.last_seen_utime = 10 * kSecond;
  mover.recent_scans = 0xffu;  // lived 8 scans
  mover.recent_hits = 0x15u;   // newest first: hit, miss, hit, miss, hit: 3 of 5
  mover.recent_visible_misses = 0x2u;  // the first miss where it should have been seen
  EXPECT_EQ(HitsInLastScans(mover, 5), 3);
  EXPECT_EQ(MissesInLastScans(mover, 5), 2);
  EXPECT_EQ(VisibleMissesInLastScans(mover, 5), 1);
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond, options));
  mover.recent_visible_misses = 0xau;  // both misses where it should have been seen
  EXPECT_FALSE(ReportedTrack(mover, true, 10 * kSecond, options));
  options.report_other_hits = 3;
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond, options));
  options.report_other_hits = 0;  // off
  EXPECT_TRUE(ReportedTrack(mover, true, 10 * kSecond, options));
  options = TrackManagementOptions();
  // A walking person: 3 of 5 whatever the misses were.
  ObjectRecord person = mover;
  person.kind = ObjectKind::kPerson;
  person.recent_visible_misses = 0u;
  EXPECT_TRUE(ReportedTrack(person, true, 10 * kSecond, options));
  person.recent_hits = 0x11u;  // hit, miss, miss, miss, hit: 2 of 5
  EXPECT_FALSE(ReportedTrack(person, true, 10 * kSecond, options));
  person.object_class = ObjectClass::kUndecided;  // not walking: the 0.5 s rule alone
  EXPECT_TRUE(ReportedTrack(person, true, 10 * kSecond, options));
  // A person that lived 3 scans and was measured in each: no miss, reported at once.
  person.object_class = ObjectClass::kMoving;
  person.recent_scans = 0x7u;
  person.recent_hits = 0x7u;
  EXPECT_TRUE(ReportedTrack(person, true, 10 * kSecond, options));
  // A static landmark that is no person is the map: reported while confirmed.
  ObjectRecord landmark = NewObjectRecord(2, 0, ObjectClass::kStatic);
  landmark.confirmed = true;
  EXPECT_TRUE(ReportedTrack(landmark, false, 60 * kSecond, options));
}

// RecordHit and RecordMiss keep the three histories.
TEST(TrackManagementTest, HitsAndMissesKeepTheirHistories) {
  TrackManagementOptions options;
  ObjectRecord r = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  RecordMiss(0.1, true, true, &r);    // should have been seen
  RecordMiss(0.1, true, false, &r);   // in a shadow
  RecordHit(kSecond / 2, options, &r);
  EXPECT_EQ(r.recent_scans, 0xfu);
  EXPECT_EQ(r.recent_hits, 0x9u);
  EXPECT_EQ(r.recent_visible_misses, 0x4u);
  EXPECT_EQ(MissesInLastScans(r, 5), 2);
  EXPECT_EQ(VisibleMissesInLastScans(r, 5), 1);
}

// With confirm_person_hits 2 (the default), two scans of person features in the window confirm
// a person; anything else needs three.
TEST(TrackManagementTest, APersonIsConfirmedByConfirmPersonHitsOfTheLastFiveScans) {
  TrackManagementOptions options;
  EXPECT_EQ(options.confirm_person_hits, 2);
  EXPECT_EQ(options.confirm_hits, 3);
  ObjectRecord person = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  person.kind = ObjectKind::kPerson;
  ObjectRecord other = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  for (ObjectRecord* r : {&person, &other}) {
    RecordMiss(0.1, true, true, r);
    RecordHit(kSecond / 5, options, r);
  }
  EXPECT_TRUE(person.confirmed);
  EXPECT_FALSE(other.confirmed);
  RecordHit(kSecond * 3 / 10, options, &other);
  EXPECT_TRUE(other.confirmed);
}

TEST(TrackManagementTest, WindowsMustHoldTheirHits) {
  EstimatorOptions options;
  options.tracks.report_other_hits = 6;
  EXPECT_EQ(CheckEstimatorOptions(options),
            "tracks_report_window_scans must be >= tracks_report_person_hits and "
            "tracks_report_other_hits");
  options = EstimatorOptions();
  options.tracks.confirm_person_hits = 6;
  EXPECT_EQ(CheckEstimatorOptions(options),
            "tracks_confirm_window_scans must be 0 or >= tracks_confirm_person_hits");
}

}  // namespace
}  // namespace slammtt
