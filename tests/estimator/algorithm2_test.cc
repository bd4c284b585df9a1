// Behaviours of Algorithm 2 (paper: Bahraini, Bozorg and Rad, Mechatronics 2018) that no other
// test pins down: the adaptive hypothesis count of eq. 16 and its cap N (line 7.b), the split
// of the compatibility matrix J into level 1 and RANSAC (lines 5-7), confirmation and pruning
// (lines 11-13, section 5.1's 3.5 s), the prior of a new object (line 13) and the third level
// with gate d2 (line 9). Each test was seen to fail with its behaviour removed.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/gating.h"
#include "estimator/ml_ransac.h"
#include "estimator/slam_state.h"
#include "estimator/track_management.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;
constexpr int64_t kScan = kSecond / 10;  // scans 0.1 s apart

// ---------------------------------------------------------------------------------------------
// 1. Eq. 16 with m = 1: N = log(1 - p) / log(1 - w).

TEST(RequiredHypothesesTest, FollowsEquationSixteenWithOnePointSamples) {
  // w = 0.5, p = 0.99: log(0.01) / log(0.5) = 6.6439.
  EXPECT_NEAR(RequiredHypotheses(0.5, 0.99), 6.643856189774724, 1e-12);
  EXPECT_NEAR(RequiredHypotheses(0.1, 0.99), std::log(0.01) / std::log(0.9), 1e-12);  // 43.7
  EXPECT_NEAR(RequiredHypotheses(0.9, 0.99), 2.0, 1e-12);  // log(0.01) / log(0.1)
  // p enters: a lower success probability needs fewer hypotheses.
  EXPECT_NEAR(RequiredHypotheses(0.5, 0.95), std::log(0.05) / std::log(0.5), 1e-12);  // 4.32
}

TEST(RequiredHypothesesTest, EdgeCases) {
  // No inlier: no number of hypotheses reaches p (the cap N bounds the draw).
  EXPECT_EQ(RequiredHypotheses(0.0, 0.99), std::numeric_limits<double>::infinity());
  // Every pair an inlier: the first hypothesis is one, nothing more is needed.
  EXPECT_EQ(RequiredHypotheses(1.0, 0.99), 0.0);
}

TEST(RequiredHypothesesTest, DecreasesAsTheInlierRatioGrows) {
  double previous = RequiredHypotheses(0.01, 0.99);
  EXPECT_GT(previous, 400.0);  // 458.2
  for (int k = 2; k <= 99; ++k) {
    const double n = RequiredHypotheses(0.01 * k, 0.99);
    EXPECT_LT(n, previous) << "inlier ratio " << 0.01 * k;
    EXPECT_GT(n, 0.0);
    previous = n;
  }
}

// ---------------------------------------------------------------------------------------------
// 2. The cap N (max_hypotheses) holds.

// One measurement and 40 objects around it, all inside its gate: every hypothesis (the
// measurement with one object) has a consensus of 1 (the other pairs share its measurement),
// so eq. 16 asks for log(0.01) / log(1 - 1/40) = 182 hypotheses, more than the 40 distinct ones.
struct CrowdAroundOneMeasurement {
  SlamState state{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
  std::vector<PointMeasurement> measurements;
  std::vector<ObjectPrediction> predictions;
  std::vector<Candidate> pairs;
  static constexpr int kObjects = 40;
  CrowdAroundOneMeasurement() {
    const Eigen::Matrix<double, 2, 3> no_robot = Eigen::Matrix<double, 2, 3>::Zero();
    for (int j = 0; j < kObjects; ++j) {
      ObjectRecord record;
      record.id = j + 1;
      const double angle = 2.0 * M_PI * j / kObjects;
      state.AddObject(Eigen::Vector2d(5.0 + 0.1 * std::cos(angle), 0.1 * std::sin(angle)),
                      no_robot, 0.25 * Eigen::Matrix2d::Identity(), record);
    }
    PointMeasurement z;
    z.range_bearing = Eigen::Vector2d(5.0, 0.0);
    z.covariance = Eigen::Vector2d(0.04, 0.001).asDiagonal();
    measurements.push_back(z);
    predictions = PredictObservations(state, SensorMount());
    pairs = GatePairs(measurements, predictions, 9.21);
  }
  RansacOutcome Run(int max_hypotheses, uint64_t seed) const {
    RansacOptions options;
    options.max_hypotheses = max_hypotheses;
    std::mt19937_64 rng(seed);
    return RunOnePointRansac(state, measurements, predictions, pairs, pairs, SensorMount(),
                             options, &rng);
  }
};

TEST(RansacCapTest, NeverMoreHypothesesThanTheCap) {
  const CrowdAroundOneMeasurement scene;
  ASSERT_EQ(scene.pairs.size(), static_cast<size_t>(CrowdAroundOneMeasurement::kObjects));
  ASSERT_GT(RequiredHypotheses(1.0 / CrowdAroundOneMeasurement::kObjects, 0.99), 100.0);
  // Uncapped (the paper's N = 1000), every distinct pair is drawn: eq. 16 asks for more.
  EXPECT_EQ(scene.Run(1000, 1).hypotheses, CrowdAroundOneMeasurement::kObjects);
  for (int cap : {1, 5, 17}) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      const RansacOutcome outcome = scene.Run(cap, seed);
      EXPECT_EQ(outcome.hypotheses, cap) << "cap " << cap << ", seed " << seed;
      EXPECT_EQ(outcome.consensus.size(), 1u);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 3. SplitCompatibility: level 1 gets the pairs unambiguous both ways, RANSAC the rest.

bool Contains(const std::vector<Candidate>& pairs, int measurement, int object) {
  for (const Candidate& c : pairs) {
    if (c.measurement == measurement && c.object == object) return true;
  }
  return false;
}

TEST(SplitCompatibilityTest, OneToOnePairsAllGoToLevelOne) {
  const std::vector<Candidate> j = {{0, 2, 1.0}, {1, 0, 2.0}, {2, 1, 3.0}};
  const CompatibilitySplit split = SplitCompatibility(j, 3, 3);
  EXPECT_EQ(split.unambiguous.size(), 3u);
  EXPECT_TRUE(split.ambiguous.empty());
  EXPECT_TRUE(Contains(split.unambiguous, 0, 2));
  EXPECT_TRUE(Contains(split.unambiguous, 1, 0));
  EXPECT_TRUE(Contains(split.unambiguous, 2, 1));
}

TEST(SplitCompatibilityTest, AMeasurementWithTwoCandidatesGoesToRansac) {
  // Measurement 0 fits objects 0 and 1 (a row of J with two ones); measurement 1 fits only
  // object 2.
  const std::vector<Candidate> j = {{0, 0, 1.0}, {0, 1, 2.0}, {1, 2, 0.5}};
  const CompatibilitySplit split = SplitCompatibility(j, 2, 3);
  ASSERT_EQ(split.unambiguous.size(), 1u);
  EXPECT_TRUE(Contains(split.unambiguous, 1, 2));
  ASSERT_EQ(split.ambiguous.size(), 2u);
  EXPECT_TRUE(Contains(split.ambiguous, 0, 0));
  EXPECT_TRUE(Contains(split.ambiguous, 0, 1));
}

TEST(SplitCompatibilityTest, TwoMeasurementsSharingOneObjectGoToRansac) {
  // Measurements 0 and 1 each have one candidate, the same object 1 (a column of J with two
  // ones): unambiguous by row, not by column.
  const std::vector<Candidate> j = {{0, 1, 1.0}, {1, 1, 2.0}, {2, 0, 0.5}};
  const CompatibilitySplit split = SplitCompatibility(j, 3, 2);
  ASSERT_EQ(split.unambiguous.size(), 1u);
  EXPECT_TRUE(Contains(split.unambiguous, 2, 0));
  ASSERT_EQ(split.ambiguous.size(), 2u);
  EXPECT_TRUE(Contains(split.ambiguous, 0, 1));
  EXPECT_TRUE(Contains(split.ambiguous, 1, 1));
}

TEST(SplitCompatibilityTest, AMeasurementWithNoCandidateGoesToNeither) {
  // Measurement 1 has an empty row; object 2 an empty column.
  const std::vector<Candidate> j = {{0, 0, 1.0}, {2, 1, 2.0}, {3, 1, 3.0}};
  const CompatibilitySplit split = SplitCompatibility(j, 4, 3);
  EXPECT_EQ(split.unambiguous.size() + split.ambiguous.size(), j.size())
      << "every allowed pair goes to exactly one level";
  for (const std::vector<Candidate>* part : {&split.unambiguous, &split.ambiguous}) {
    for (const Candidate& c : *part) {
      EXPECT_NE(c.measurement, 1);
      EXPECT_NE(c.object, 2);
    }
  }
  ASSERT_EQ(split.unambiguous.size(), 1u);
  EXPECT_TRUE(Contains(split.unambiguous, 0, 0));
  EXPECT_TRUE(Contains(split.ambiguous, 2, 1));
  EXPECT_TRUE(Contains(split.ambiguous, 3, 1));
  // An empty J splits into nothing.
  const CompatibilitySplit none = SplitCompatibility({}, 4, 3);
  EXPECT_TRUE(none.unambiguous.empty());
  EXPECT_TRUE(none.ambiguous.empty());
}

// ---------------------------------------------------------------------------------------------
// 4. Confirmation and pruning (track_management.h).

TEST(ConfirmationTest, ATentativeObjectIsConfirmedExactlyAtConfirmHits) {
  for (int confirm_hits : {1, 2, 3, 5}) {
    TrackManagementOptions options;
    options.confirm_hits = confirm_hits;
    ObjectRecord record = NewObjectRecord(7, 0, ObjectClass::kUndecided);
    EXPECT_EQ(record.hits, 1);
    EXPECT_FALSE(record.confirmed) << "a new object is tentative";
    for (int hit = 2; hit <= confirm_hits + 1; ++hit) {
      RecordHit(hit * kScan, options, &record);
      EXPECT_EQ(record.hits, hit);
      EXPECT_EQ(record.confirmed, hit >= confirm_hits)
          << "confirm_hits " << confirm_hits << ", hit " << hit;
      EXPECT_EQ(record.last_seen_utime, hit * kScan);
    }
  }
}

// A confirmed object last seen at utime 0, judged at `unseen_s` with nothing else against it.
ObjectRecord ConfirmedRecord(ObjectClass object_class) {
  ObjectRecord record = NewObjectRecord(1, 0, object_class);
  record.hits = 10;
  record.confirmed = true;
  return record;
}

int64_t Utime(double seconds) { return static_cast<int64_t>(std::llround(seconds * kSecond)); }

TEST(PruningTest, AConfirmedObjectWithVelocityIsPrunedAfterPruneUnseenS) {
  const TrackManagementOptions options;  // prune_unseen_s 3.5 (paper section 5.1)
  ASSERT_EQ(options.prune_unseen_s, 3.5);
  // Undecided: by the time since its last measurement (occluded: unseen_in_view_s stays 0).
  const ObjectRecord undecided = ConfirmedRecord(ObjectClass::kUndecided);
  EXPECT_FALSE(ShouldPrune(undecided, true, Utime(3.4), false, 0.1, options));
  EXPECT_FALSE(ShouldPrune(undecided, true, Utime(3.5), false, 0.1, options));
  EXPECT_TRUE(ShouldPrune(undecided, true, Utime(3.6), false, 0.1, options));
  // Moving, in view but occluded: by the time its prediction spent inside the sensor's
  // geometry, accumulated scan by scan (0.1 s each).
  ObjectRecord moving = ConfirmedRecord(ObjectClass::kMoving);
  int scans = 0;
  for (; scans < 34; ++scans) RecordMiss(0.1, true, false, &moving);
  EXPECT_FALSE(ShouldPrune(moving, true, scans * kScan, false, 0.1, options));
  for (; scans < 36; ++scans) RecordMiss(0.1, true, false, &moving);
  EXPECT_TRUE(ShouldPrune(moving, true, scans * kScan, false, 0.1, options));
  // Another prune_unseen_s moves the threshold with it.
  TrackManagementOptions longer = options;
  longer.prune_unseen_s = 5.0;
  EXPECT_FALSE(ShouldPrune(undecided, true, Utime(4.0), false, 0.1, longer));
  EXPECT_FALSE(ShouldPrune(moving, true, scans * kScan, false, 0.1, longer));
  EXPECT_TRUE(ShouldPrune(undecided, true, Utime(5.1), false, 0.1, longer));
}

TEST(PruningTest, ATentativeObjectIsPrunedAfterTentativePruneUnseenS) {
  const TrackManagementOptions options;  // tentative_prune_unseen_s 1.0
  ASSERT_EQ(options.tentative_prune_unseen_s, 1.0);
  const ObjectRecord tentative = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  ASSERT_FALSE(tentative.confirmed);
  for (bool has_velocity : {true, false}) {
    EXPECT_FALSE(ShouldPrune(tentative, has_velocity, Utime(0.9), false, 0.1, options));
    EXPECT_TRUE(ShouldPrune(tentative, has_velocity, Utime(1.1), false, 0.1, options));
  }
  // The same time does not prune a confirmed one.
  EXPECT_FALSE(ShouldPrune(ConfirmedRecord(ObjectClass::kUndecided), true, Utime(1.1), false,
                           0.1, options));
  TrackManagementOptions slower = options;
  slower.tentative_prune_unseen_s = 2.0;
  EXPECT_FALSE(ShouldPrune(tentative, true, Utime(1.9), false, 0.1, slower));
  EXPECT_TRUE(ShouldPrune(tentative, true, Utime(2.1), false, 0.1, slower));
}

// confirm_hits 3 of confirm_window_scans 5: one hit and three misses leave no window with
// three hits that holds the hit; it is pruned at once, not 1 s after its hit.
TEST(PruningTest, ATentativeObjectThatCanNoLongerBeConfirmedIsPrunedAtOnce) {
  TrackManagementOptions options;
  ASSERT_FALSE(options.tentative_prune_unconfirmable) << "off by default";
  options.tentative_prune_unconfirmable = true;
  ASSERT_EQ(options.confirm_hits, 3);
  ASSERT_EQ(options.confirm_window_scans, 5);
  ObjectRecord tentative = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  for (int miss = 1; miss <= 2; ++miss) {
    RecordMiss(0.1, true, true, &tentative);
    EXPECT_TRUE(CanStillConfirm(tentative, options)) << miss << " misses: hit, hit, hit next";
    EXPECT_FALSE(ShouldPrune(tentative, true, miss * kScan, false, 0.1, options));
  }
  RecordMiss(0.1, true, true, &tentative);
  EXPECT_FALSE(CanStillConfirm(tentative, options));
  EXPECT_TRUE(ShouldPrune(tentative, true, 3 * kScan, false, 0.1, options));
  // Off: the old rule, after tentative_prune_unseen_s.
  TrackManagementOptions off = options;
  off.tentative_prune_unconfirmable = false;
  EXPECT_FALSE(ShouldPrune(tentative, true, 3 * kScan, false, 0.1, off));
  EXPECT_TRUE(ShouldPrune(tentative, true, Utime(1.1), false, 0.1, off));
  // Without a window (confirm_hits at any time) nothing is unconfirmable.
  TrackManagementOptions any_time = options;
  any_time.confirm_window_scans = 0;
  EXPECT_FALSE(ShouldPrune(tentative, true, 3 * kScan, false, 0.1, any_time));
  // Two hits, then misses: after two, the window ending next scan holds both hits and a third;
  // after three, every window that holds one of its hits holds three misses.
  ObjectRecord twice = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  RecordHit(kScan, options, &twice);
  RecordMiss(0.1, true, true, &twice);
  RecordMiss(0.1, true, true, &twice);
  EXPECT_FALSE(ShouldPrune(twice, true, 3 * kScan, false, 0.1, options)) << "hit, hit, one more";
  RecordMiss(0.1, true, true, &twice);
  EXPECT_TRUE(ShouldPrune(twice, true, 4 * kScan, false, 0.1, options));
  // A hit this scan always leaves a way to confirmation.
  RecordHit(5 * kScan, options, &twice);
  EXPECT_TRUE(CanStillConfirm(twice, options));
}

// other_tentative_prune_unconfirmable: the rule for objects that are not people only; a
// person's tentative track that could no longer be confirmed waits tentative_prune_unseen_s.
TEST(PruningTest, TheRuleForOtherObjectsSparesAPersonThatCanNoLongerBeConfirmed) {
  TrackManagementOptions options;
  ASSERT_FALSE(options.other_tentative_prune_unconfirmable) << "off by default";
  options.other_tentative_prune_unconfirmable = true;
  ObjectRecord person = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  person.person_hits = 1;
  person.kind = ObjectKind::kPerson;
  ObjectRecord other = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  for (int miss = 1; miss <= 4; ++miss) {
    RecordMiss(0.1, true, true, &person);
    RecordMiss(0.1, true, true, &other);
  }
  ASSERT_FALSE(CanStillConfirm(person, options));
  ASSERT_FALSE(CanStillConfirm(other, options));
  EXPECT_FALSE(ShouldPrune(person, true, 4 * kScan, false, 0.1, options));
  EXPECT_TRUE(ShouldPrune(other, true, 4 * kScan, false, 0.1, options));
  EXPECT_TRUE(ShouldPrune(person, true, Utime(1.1), false, 0.1, options)) << "unseen 1.1 s";
}

TEST(PruningTest, APersonNeedsFewerHitsSoItMayMissMore) {
  TrackManagementOptions options;
  options.tentative_prune_unconfirmable = true;
  ASSERT_EQ(options.confirm_person_hits, 2);
  ObjectRecord person = NewObjectRecord(1, 0, ObjectClass::kUndecided);
  person.person_hits = 1;
  person.kind = ObjectKind::kPerson;
  ObjectRecord other = NewObjectRecord(2, 0, ObjectClass::kUndecided);
  for (int miss = 1; miss <= 3; ++miss) {
    RecordMiss(0.1, true, true, &person);
    RecordMiss(0.1, true, true, &other);
  }
  EXPECT_TRUE(CanStillConfirm(person, options)) << "its hit and one more in the window";
  EXPECT_FALSE(ShouldPrune(person, true, 3 * kScan, false, 0.1, options));
  EXPECT_TRUE(ShouldPrune(other, true, 3 * kScan, false, 0.1, options));
  RecordMiss(0.1, true, true, &person);
  EXPECT_TRUE(ShouldPrune(person, true, 4 * kScan, false, 0.1, options));
}

FeatureReading Feature(double range_m, double bearing_rad) {
  FeatureReading f;
  f.range_m = range_m;
  f.bearing_rad = bearing_rad;
  return f;
}

// A robot standing still (exact zero odometry at every scan) sees two posts every 0.1 s for
// 3 s, long enough for both to become confirmed STATIC landmarks; then post B is taken away.
// It is in view and nothing hides it, so it must go between 3.5 s (section 5.1) and 3.5 s +
// one scan after its last sighting; post A stays.
TEST(PruningTest, ALandmarkThatVanishesFromViewIsRemovedAfterThreeAndAHalfSeconds) {
  const EstimatorOptions options;
  ASSERT_EQ(options.tracks.static_prune_unseen_in_view_s, 3.5);
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  const double a_range = 4.0, a_bearing = 0.3, b_range = 5.0, b_bearing = -0.6;
  int64_t utime = kSecond;
  auto step = [&](bool with_b) {
    OdometryReading standing;
    standing.utime = utime;
    estimator.AddOdometry(standing);
    ScanInput scan;
    scan.utime = utime;
    scan.features.push_back(Feature(a_range, a_bearing));
    if (with_b) scan.features.push_back(Feature(b_range, b_bearing));
    const ScanResult result = estimator.ProcessScan(scan, &rng);
    utime += kScan;
    return result;
  };
  ScanResult last;
  for (int k = 0; k < 30; ++k) last = step(true);
  ASSERT_EQ(last.objects.size(), 2u);
  for (const ObjectEstimate& o : last.objects) {
    ASSERT_EQ(o.object_class, ObjectClass::kStatic);
    ASSERT_TRUE(o.confirmed);
  }
  const int64_t b_id = last.objects[1].id;
  const int64_t b_last_seen = last.utime;
  auto has_b = [&](const ScanResult& r) {
    for (const ObjectEstimate& o : r.objects) {
      if (o.id == b_id) return true;
    }
    return false;
  };
  for (int k = 1; k <= 36; ++k) {
    const ScanResult r = step(false);
    ASSERT_TRUE(r.processed);
    const double unseen_s = static_cast<double>(r.utime - b_last_seen) / kSecond;
    if (k <= 34) {
      EXPECT_TRUE(has_b(r)) << "removed after " << unseen_s << " s";
    } else if (k == 36) {
      EXPECT_FALSE(has_b(r)) << "still there after " << unseen_s << " s";
    }
    ASSERT_FALSE(r.objects.empty()) << "post A, seen every scan, is kept";
    EXPECT_EQ(r.counts.new_objects, 0);
  }
  EXPECT_EQ(estimator.state().num_objects(), 1);
}

// ---------------------------------------------------------------------------------------------
// 5 and 6. New objects and level 3, with one object whose predicted measurement is known.

// Scan 1 (robot at the origin, known exactly, no odometry) creates one object from a feature at
// 5 m, bearing 0.2 rad, with the default R (0.2 m, 2 degrees). Scan 2 comes 1 us later, so the
// prediction changes the object's covariance by about 1e-12: the NIS the estimator sees is the
// one computed here from the state after scan 1. Scan 2's feature is displaced in range so that
// its NIS to the object is `nis`.
struct KnownObjectScene {
  Estimator estimator;
  std::mt19937_64 rng{1};
  ScanResult first;
  Eigen::Vector2d predicted = Eigen::Vector2d::Zero();
  Eigen::Matrix2d innovation_covariance = Eigen::Matrix2d::Zero();

  explicit KnownObjectScene(const EstimatorOptions& options) : estimator(options) {
    ScanInput scan;
    scan.utime = kSecond;
    scan.features.push_back(Feature(5.0, 0.2));
    first = estimator.ProcessScan(scan, &rng);
    const std::vector<ObjectPrediction> p =
        PredictObservations(estimator.state(), estimator.options().sensor);
    predicted = p[0].range_bearing;
    const double r = options.default_range_sigma_m, b = options.default_bearing_sigma_rad;
    innovation_covariance = p[0].hph + Eigen::Vector2d(r * r, b * b).asDiagonal().toDenseMatrix();
  }

  // The second scan with one feature at NIS `nis` from the object (displaced in range).
  ScanResult SecondScanAtNis(double nis) {
    const double range_offset = std::sqrt(nis / innovation_covariance.inverse()(0, 0));
    ScanInput scan;
    scan.utime = kSecond + 1;
    scan.features.push_back(Feature(predicted(0) + range_offset, predicted(1)));
    return estimator.ProcessScan(scan, &rng);
  }
};

TEST(NewObjectTest, StartsUndecidedTentativeWithZeroVelocityAndItsPrior) {
  for (double sigma : {1.0, 0.7}) {
    EstimatorOptions options;
    options.new_object_velocity_sigma_mps = sigma;
    KnownObjectScene scene(options);
    ASSERT_EQ(scene.first.objects.size(), 1u);
    EXPECT_EQ(scene.first.counts.new_objects, 1);
    const ObjectEstimate& o = scene.first.objects[0];
    EXPECT_EQ(o.object_class, ObjectClass::kUndecided);
    EXPECT_FALSE(o.confirmed);
    EXPECT_EQ(scene.estimator.NumTentative(), 1);
    EXPECT_EQ(o.hits, 1);
    EXPECT_EQ(o.velocity, Eigen::Vector2d::Zero());
    // Velocity covariance sigma^2 I, independent of the position.
    EXPECT_EQ(o.covariance(2, 2), sigma * sigma);
    EXPECT_EQ(o.covariance(3, 3), sigma * sigma);
    EXPECT_EQ(o.covariance(2, 3), 0.0);
    EXPECT_TRUE((o.covariance.block<2, 2>(0, 2).isZero(0.0)));
    // Its position is the feature's point: 5 m at 0.2 rad.
    EXPECT_NEAR(o.position.x(), 5.0 * std::cos(0.2), 1e-12);
    EXPECT_NEAR(o.position.y(), 5.0 * std::sin(0.2), 1e-12);
  }
}

TEST(NewObjectTest, OnlyOutsideGateDnOfEveryObject) {
  const EstimatorOptions options;  // d1 9.21, d2 13.82, dn 20
  ASSERT_EQ(options.new_object_gate_dn_chi2, 20.0);
  {
    // NIS 16: outside d1 and d2, inside dn. Neither associated nor a new object.
    KnownObjectScene scene(options);
    const ScanResult r = scene.SecondScanAtNis(16.0);
    EXPECT_EQ(r.counts.level1_updates + r.counts.level2_updates + r.counts.level3_updates, 0);
    EXPECT_EQ(r.counts.new_objects, 0);
    ASSERT_EQ(r.objects.size(), 1u);
    EXPECT_EQ(r.objects[0].hits, 1);
  }
  {
    // NIS 24: outside dn. A second object starts.
    KnownObjectScene scene(options);
    const ScanResult r = scene.SecondScanAtNis(24.0);
    EXPECT_EQ(r.counts.level1_updates + r.counts.level2_updates + r.counts.level3_updates, 0);
    EXPECT_EQ(r.counts.new_objects, 1);
    EXPECT_EQ(r.objects.size(), 2u);
  }
}

// Two posts side by side, the second's feature inside gate dn of the first's object (NIS 16)
// from the scan it appears in, about 1.1 m behind it. The first post's object takes its own
// feature; on (new_object_gate_skips_claimed_objects, with the separation below the posts') the
// second post starts its own object at
// once, and over 3 s of a robot standing still both become confirmed STATIC landmarks with no
// MOVING object on the way. Off, the first post's gate keeps the second from being mapped then.
TEST(NewObjectTest, ASecondPostInsideTheGateOfAMeasuredOneStartsItsOwnObject) {
  for (const bool skips : {true, false}) {
    EstimatorOptions options;
    options.new_object_gate_skips_claimed_objects = skips;
    options.new_object_beside_claimed_min_separation_m = 0.5;
    KnownObjectScene scene(options);
    const double range_offset = std::sqrt(16.0 / scene.innovation_covariance.inverse()(0, 0));
    const Eigen::Vector2d second(scene.predicted(0) + range_offset, scene.predicted(1));
    int64_t utime = kSecond + 1;
    auto step = [&]() {
      OdometryReading standing;
      standing.utime = utime;
      scene.estimator.AddOdometry(standing);
      ScanInput scan;
      scan.utime = utime;
      scan.features.push_back(Feature(scene.predicted(0), scene.predicted(1)));
      scan.features.push_back(Feature(second(0), second(1)));
      utime += kScan;
      return scene.estimator.ProcessScan(scan, &scene.rng);
    };
    const ScanResult appears = step();
    EXPECT_EQ(appears.counts.level1_updates, 1);
    if (!skips) {
      EXPECT_EQ(appears.counts.new_objects, 0) << "the old behaviour: blocked by the first post";
      continue;
    }
    EXPECT_EQ(appears.counts.new_objects, 1);
    ScanResult last = appears;
    for (int k = 0; k < 30; ++k) {
      last = step();
      EXPECT_EQ(last.counts.new_objects, 0);
      for (const ObjectEstimate& o : last.objects) {
        EXPECT_NE(o.object_class, ObjectClass::kMoving) << "object " << o.id << " scan " << k;
      }
    }
    ASSERT_EQ(last.objects.size(), 2u);
    for (const ObjectEstimate& o : last.objects) {
      EXPECT_EQ(o.object_class, ObjectClass::kStatic) << "object " << o.id;
      EXPECT_TRUE(o.confirmed);
    }
  }
}

TEST(LevelThreeTest, APairBetweenD1AndD2IsAssociatedOnlyWithLevelThree) {
  EstimatorOptions with;  // level3 true, d1 9.21, d2 13.82
  ASSERT_TRUE(with.level3);
  ASSERT_EQ(with.gate_d1_chi2, 9.21);
  ASSERT_EQ(with.gate_d2_chi2, 13.82);
  EstimatorOptions without = with;
  without.level3 = false;
  {
    KnownObjectScene scene(with);
    const ScanResult r = scene.SecondScanAtNis(11.0);
    EXPECT_EQ(r.counts.level1_updates, 0);
    EXPECT_EQ(r.counts.level2_updates, 0);
    EXPECT_EQ(r.counts.level3_updates, 1);
    EXPECT_EQ(r.counts.new_objects, 0);
    ASSERT_EQ(r.objects.size(), 1u);
    EXPECT_EQ(r.objects[0].hits, 2);
    EXPECT_EQ(r.objects[0].last_seen_utime, kSecond + 1);
  }
  {
    KnownObjectScene scene(without);
    const ScanResult r = scene.SecondScanAtNis(11.0);
    EXPECT_EQ(r.counts.level1_updates + r.counts.level2_updates + r.counts.level3_updates, 0);
    EXPECT_EQ(r.counts.new_objects, 0) << "inside dn: no new object either";
    ASSERT_EQ(r.objects.size(), 1u);
    EXPECT_EQ(r.objects[0].hits, 1);
  }
  // Controls: inside d1 it is level 1 either way; beyond d2 level 3 takes it neither.
  for (const EstimatorOptions& options : {with, without}) {
    KnownObjectScene inside(options);
    EXPECT_EQ(inside.SecondScanAtNis(8.0).counts.level1_updates, 1);
    KnownObjectScene beyond(options);
    const ScanResult r = beyond.SecondScanAtNis(15.0);
    EXPECT_EQ(r.counts.level1_updates + r.counts.level2_updates + r.counts.level3_updates, 0);
  }
}

}  // namespace
}  // namespace slammtt
