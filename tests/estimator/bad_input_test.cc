// Every kind of bad or unusual input: rejected or handled, counted, described, never a crash,
// a NaN or a broken covariance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <random>

#include "estimator/estimator.h"

namespace slammtt {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

FeatureReading Feature(double range_m, double bearing_rad) {
  FeatureReading f;
  f.range_m = range_m;
  f.bearing_rad = bearing_rad;
  return f;
}

OdometryReading Odometry(int64_t utime, double x_m, double linear_mps = 0.0) {
  OdometryReading r;
  r.utime = utime;
  r.pose = Eigen::Vector3d(x_m, 0.0, 0.0);
  r.linear_mps = linear_mps;
  return r;
}

ScanInput Scan(int64_t utime, std::vector<FeatureReading> features) {
  ScanInput s;
  s.utime = utime;
  s.features = std::move(features);
  return s;
}

void ExpectHealthy(const Estimator& estimator) {
  const SlamState& state = estimator.state();
  ASSERT_TRUE(state.mean().allFinite());
  ASSERT_TRUE(state.covariance().allFinite());
  ASSERT_EQ(state.covariance(), state.covariance().transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(state.covariance());
  EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-9 * std::max(1.0, state.covariance().trace()));
}

class BadInputTest : public ::testing::Test {
 protected:
  std::mt19937_64 rng_{1};
};

TEST_F(BadInputTest, NonFiniteAndOutOfRangeFeaturesAreRejectedAndCounted) {
  Estimator estimator{EstimatorOptions{}};
  FeatureReading negative_variance = Feature(5.0, 0.1);
  negative_variance.range_var_m2 = -0.1;
  negative_variance.bearing_var_rad2 = 0.01;
  FeatureReading not_psd = Feature(5.0, 0.2);
  not_psd.range_var_m2 = 0.01;
  not_psd.bearing_var_rad2 = 0.01;
  not_psd.range_bearing_cov_m_rad = 0.5;
  FeatureReading nan_variance = Feature(5.0, 0.3);
  nan_variance.range_var_m2 = kNan;
  const ScanResult result = estimator.ProcessScan(
      Scan(100000, {Feature(kNan, 0.0), Feature(4.0, kInf), Feature(-1.0, 0.0),
                    Feature(31.0, 0.0), Feature(0.001, 0.0), Feature(5.0, 4.0), negative_variance,
                    not_psd, nan_variance, Feature(6.0, 0.5), Feature(7.0, -0.5)}),
      &rng_);
  ASSERT_TRUE(result.processed);
  EXPECT_EQ(result.counts.features, 11);
  EXPECT_EQ(result.counts.features_rejected, 9);
  EXPECT_EQ(estimator.counters().features_rejected, 9);
  EXPECT_EQ(result.counts.new_objects, 2);
  EXPECT_NE(estimator.last_event().find("rejected"), std::string::npos);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, OlderScansAndOdometryAreDroppedAndCounted) {
  Estimator estimator{EstimatorOptions{}};
  EXPECT_TRUE(estimator.AddOdometry(Odometry(100000, 0.0)));
  EXPECT_TRUE(estimator.ProcessScan(Scan(200000, {Feature(5.0, 0.0)}), &rng_).processed);
  EXPECT_FALSE(estimator.ProcessScan(Scan(200000, {Feature(5.0, 0.0)}), &rng_).processed);
  EXPECT_FALSE(estimator.ProcessScan(Scan(150000, {Feature(5.0, 0.0)}), &rng_).processed);
  EXPECT_TRUE(estimator.AddOdometry(Odometry(250000, 0.1)));
  EXPECT_FALSE(estimator.AddOdometry(Odometry(250000, 0.2)));
  EXPECT_FALSE(estimator.AddOdometry(Odometry(240000, 0.2)));
  EXPECT_EQ(estimator.counters().messages_out_of_order, 4);
  EXPECT_EQ(estimator.counters().scans_processed, 1);
  EXPECT_EQ(estimator.counters().odometry_processed, 2);
  EXPECT_NE(estimator.last_event().find("dropped"), std::string::npos);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, NonFiniteOdometryIsRejected) {
  Estimator estimator{EstimatorOptions{}};
  OdometryReading bad = Odometry(100000, kNan);
  EXPECT_FALSE(estimator.AddOdometry(bad));
  bad = Odometry(100000, 0.0, kInf);
  EXPECT_FALSE(estimator.AddOdometry(bad));
  EXPECT_EQ(estimator.counters().odometry_rejected, 2);
  EXPECT_TRUE(estimator.AddOdometry(Odometry(100000, 0.0)));
  EXPECT_TRUE(estimator.ProcessScan(Scan(100000, {}), &rng_).processed);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, EmptyScanIsAValidScan) {
  Estimator estimator{EstimatorOptions{}};
  for (int k = 1; k <= 20; ++k) {
    estimator.AddOdometry(Odometry(k * 100000, 0.05 * k, 0.5));
    const ScanResult result = estimator.ProcessScan(Scan(k * 100000, {}), &rng_);
    ASSERT_TRUE(result.processed);
    EXPECT_TRUE(result.objects.empty());
  }
  EXPECT_EQ(estimator.counters().scans_processed, 20);
  EXPECT_EQ(estimator.counters().features_rejected, 0);
  // Odometry alone moved the robot 0.05 m per scan along x (the first reading anchors it).
  EXPECT_NEAR(estimator.state().robot_pose()(0), 0.95, 1e-9);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, TimeGapInflatesInsteadOfTrustingTheLongPrediction) {
  EstimatorOptions options;
  options.max_time_gap_s = 1.0;
  // A 3 s pause of both streams, taken at once: this test is about the inflation, not about
  // how many messages confirm a jump ahead (the next tests).
  options.time_jump_forward_s = 10.0;
  options.classifier.still_hold_s = 100.0;  // keep the objects' velocity states for the check
  auto run = [&](int64_t gap_us) {
    Estimator estimator(options);
    std::mt19937_64 rng(1);
    int64_t t = 0;
    for (int k = 0; k < 10; ++k) {
      t += 100000;
      estimator.AddOdometry(Odometry(t, 0.0));
      estimator.ProcessScan(Scan(t, {Feature(5.0, 0.3), Feature(6.0, -0.4)}), &rng);
    }
    t += gap_us;
    estimator.AddOdometry(Odometry(t, 0.0));
    estimator.ProcessScan(Scan(t, {}), &rng);
    return estimator;
  };
  const Estimator normal = run(900000);
  const Estimator gap = run(3000000);
  EXPECT_EQ(normal.counters().time_gaps, 0);
  EXPECT_EQ(gap.counters().time_gaps, 1);
  EXPECT_NE(gap.last_event().find("inflated"), std::string::npos);
  // The robot's uncertainty after the gap is larger than the odometry alone would say, and the
  // movers' velocity uncertainty is larger too.
  EXPECT_GT(gap.state().robot_covariance()(0, 0), normal.state().robot_covariance()(0, 0) + 1.0);
  ASSERT_GT(gap.state().num_objects(), 0);
  ASSERT_GT(normal.state().num_objects(), 0);
  const StateObject& mover = gap.state().object(0);
  ASSERT_TRUE(mover.has_velocity());
  const double velocity_var =
      gap.state().covariance()(mover.velocity_index, mover.velocity_index);
  const StateObject& mover_normal = normal.state().object(0);
  EXPECT_GT(velocity_var, normal.state().covariance()(mover_normal.velocity_index,
                                                       mover_normal.velocity_index));
  ExpectHealthy(gap);
}

// A gap of any length, up to a new time base years ahead, is one inflated prediction of a
// bounded length: the covariance stays positive semi-definite and the estimator goes on. Five
// posts all around, still odometry, 20 scans, the gap, 40 scans. A gap beyond
// time_jump_forward_s (2 s) is a jump: its first two scans and odometry readings are dropped,
// the third of each confirms the new time base (time_base.h).
TEST_F(BadInputTest, GapsOfAnyLengthKeepTheCovarianceHealthy) {
  const std::vector<FeatureReading> posts = {Feature(5.0, 0.1), Feature(7.0, -0.5),
                                             Feature(4.0, 1.0), Feature(9.0, 2.0),
                                             Feature(3.0, -2.5)};
  for (const double gap_s : {3.0, 1e3, 2e4, 5e4, 1e5, 1e7, 1e9}) {
    SCOPED_TRACE("gap " + std::to_string(gap_s) + " s");
    Estimator estimator{EstimatorOptions{}};
    std::mt19937_64 rng(1);
    int64_t t = 0;
    auto step = [&](int64_t dt_us) {
      t += dt_us;
      estimator.AddOdometry(Odometry(t, 0.0));
      estimator.ProcessScan(Scan(t, posts), &rng);
    };
    for (int k = 0; k < 20; ++k) step(100000);
    step(static_cast<int64_t>(gap_s * 1e6));
    ExpectHealthy(estimator);
    for (int k = 0; k < 40 && !HasFailure(); ++k) {
      step(100000);
      ExpectHealthy(estimator);
    }
    if (HasFailure()) return;  // one gap's messages are enough
    EXPECT_EQ(estimator.counters().time_gaps, 1);
    EXPECT_EQ(estimator.counters().time_jumps_rejected, 4);
    EXPECT_EQ(estimator.counters().restarts, 0);
    EXPECT_EQ(estimator.counters().scans_processed, 59);
  }
}

// utimes at the ends of int64: differences are taken without overflow, so a reading at the
// far past and then ordinary ones give one (huge) gap, counted, not a wrapped negative time
// (after the two messages of each stream that the jump ahead needs to be believed).
TEST_F(BadInputTest, UtimesAtTheEndsOfTheRangeDoNotWrap) {
  Estimator estimator{EstimatorOptions{}};
  std::mt19937_64 rng(1);
  const int64_t far_past = std::numeric_limits<int64_t>::min() + 5;
  estimator.AddOdometry(Odometry(far_past, 0.0));
  estimator.ProcessScan(Scan(far_past + 5, {Feature(5.0, 0.2), Feature(6.0, -0.3)}), &rng);
  for (int64_t t = 1100000; t <= 3000000; t += 100000) {
    estimator.AddOdometry(Odometry(t, 0.0));
    estimator.ProcessScan(Scan(t, {Feature(5.0, 0.2), Feature(6.0, -0.3)}), &rng);
    ExpectHealthy(estimator);
    if (HasFailure()) return;
  }
  EXPECT_EQ(estimator.counters().time_gaps, 1);
  EXPECT_EQ(estimator.counters().time_jumps_rejected, 4);
  EXPECT_EQ(estimator.counters().scans_processed, 19);
}

// The same log played twice into a running estimator (lcm-logplayer): the second run's
// messages lie 3 s before the newest, beyond time_jump_back_restart_s (set to 1 s here). The
// first two of each stream are held as jumps; the third odometry reading confirms the new time
// base and the estimator starts over, instead of dropping the whole second run as out of
// order. A step back shorter than the limit is still a late message, dropped.
TEST_F(BadInputTest, ALogPlayedAgainStartsTheEstimationOver) {
  EstimatorOptions options;
  options.time_jump_back_restart_s = 1.0;
  Estimator estimator(options);
  auto play_into = [&](Estimator* e, int first, int last) {
    for (int k = first; k <= last; ++k) {
      const int64_t t = 100000 * k;
      e->AddOdometry(Odometry(t, 0.05 * k, 0.5));
      e->ProcessScan(Scan(t, {Feature(5.0 - 0.05 * k, 0.2), Feature(6.0 - 0.05 * k, -0.3)}),
                     &rng_);
    }
  };
  auto play = [&]() { play_into(&estimator, 1, 30); };
  play();
  ASSERT_EQ(estimator.counters().restarts, 0);
  int64_t largest_id = 0;
  for (const StateObject& object : estimator.state().objects()) {
    largest_id = std::max(largest_id, object.record.id);
  }
  ASSERT_GT(largest_id, 0);
  EXPECT_FALSE(estimator.ProcessScan(Scan(2500000, {Feature(5.0, 0.2)}), &rng_).processed);
  EXPECT_EQ(estimator.counters().messages_out_of_order, 1);  // 0.5 s back: late, dropped
  play();
  // The odometry's third jumped reading started it over, the scans of the new run then came to
  // a fresh start.
  EXPECT_EQ(estimator.counters().restarts, 1);
  EXPECT_EQ(estimator.counters().time_jumps_rejected, 4);
  EXPECT_NE(estimator.last_event().find("started over"), std::string::npos);
  EXPECT_EQ(estimator.counters().messages_out_of_order, 1);
  EXPECT_EQ(estimator.counters().scans_processed, 58);
  // What is left is the second run from its third messages on, as a fresh estimator sees it,
  // with new identities.
  Estimator fresh(options);
  play_into(&fresh, 3, 30);
  EXPECT_NEAR((estimator.state().robot_pose() - fresh.state().robot_pose()).norm(), 0.0, 1e-12);
  ASSERT_EQ(estimator.state().num_objects(), 2);
  for (const StateObject& object : estimator.state().objects()) {
    EXPECT_GT(object.record.id, largest_id);
  }
  ExpectHealthy(estimator);
}

// One scan stamped a million seconds ahead (a corrupted utime) is dropped and counted: no
// eleven-day gap, no restart when the ordinary scans go on, nothing else lost.
TEST_F(BadInputTest, OneFarFutureUtimeIsDroppedAndTheEstimatorGoesOn) {
  Estimator estimator{EstimatorOptions{}};
  int64_t t = 0;
  for (int k = 0; k < 10; ++k) {
    t += 100000;
    estimator.AddOdometry(Odometry(t, 0.0));
    estimator.ProcessScan(Scan(t, {Feature(5.0, 0.2)}), &rng_);
  }
  EXPECT_FALSE(
      estimator.ProcessScan(Scan(t + 1000000000000, {Feature(5.0, 0.2)}), &rng_).processed);
  EXPECT_NE(estimator.last_event().find("a jump"), std::string::npos);
  for (int k = 0; k < 10; ++k) {
    t += 100000;
    estimator.AddOdometry(Odometry(t, 0.0));
    EXPECT_TRUE(estimator.ProcessScan(Scan(t, {Feature(5.0, 0.2)}), &rng_).processed);
  }
  EXPECT_EQ(estimator.counters().time_gaps, 0);
  EXPECT_EQ(estimator.counters().restarts, 0);
  EXPECT_EQ(estimator.counters().time_jumps_rejected, 1);
  EXPECT_EQ(estimator.counters().messages_out_of_order, 0);
  EXPECT_EQ(estimator.counters().scans_processed, 20);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, ScanWithoutOdometryPredictsWithTheLastVelocity) {
  Estimator estimator{EstimatorOptions{}};
  estimator.AddOdometry(Odometry(0, 0.0, 1.0));
  estimator.AddOdometry(Odometry(100000, 0.1, 1.0));
  ASSERT_TRUE(estimator.ProcessScan(Scan(100000, {}), &rng_).processed);
  const Eigen::Matrix3d before = estimator.state().robot_covariance();
  // Two scans with no odometry at all: the robot keeps moving at 1 m/s, with more noise.
  ASSERT_TRUE(estimator.ProcessScan(Scan(200000, {}), &rng_).processed);
  ASSERT_TRUE(estimator.ProcessScan(Scan(300000, {}), &rng_).processed);
  EXPECT_EQ(estimator.counters().scans_without_odometry, 2);
  EXPECT_NEAR(estimator.state().robot_pose()(0), 0.3, 1e-9);
  // Extrapolation noise: (0.3 m/s * 0.1 s)^2 per scan, on top of the odometry model's.
  EXPECT_GT(estimator.state().robot_covariance()(0, 0), before(0, 0) + 2.0 * 0.03 * 0.03);
  EXPECT_NE(estimator.last_event().find("no odometry"), std::string::npos);
  // Odometry comes back: its increment from the extrapolated point is used, nothing counted.
  estimator.AddOdometry(Odometry(400000, 0.4, 1.0));
  ASSERT_TRUE(estimator.ProcessScan(Scan(400000, {}), &rng_).processed);
  EXPECT_EQ(estimator.counters().scans_without_odometry, 2);
  EXPECT_NEAR(estimator.state().robot_pose()(0), 0.4, 1e-9);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, ScansBetweenOdometryReadingsUseTheInterpolatedMotion) {
  Estimator estimator{EstimatorOptions{}};
  estimator.AddOdometry(Odometry(0, 0.0, 1.0));
  estimator.AddOdometry(Odometry(100000, 0.1, 1.0));
  estimator.AddOdometry(Odometry(200000, 0.2, 1.0));
  ASSERT_TRUE(estimator.ProcessScan(Scan(150000, {}), &rng_).processed);
  EXPECT_NEAR(estimator.state().robot_pose()(0), 0.15, 1e-9);
  EXPECT_EQ(estimator.counters().scans_without_odometry, 0);
  ASSERT_TRUE(estimator.ProcessScan(Scan(200000, {}), &rng_).processed);
  EXPECT_NEAR(estimator.state().robot_pose()(0), 0.2, 1e-9);
}

TEST_F(BadInputTest, ObjectCapIsEnforcedAndReported) {
  EstimatorOptions options;
  options.max_objects = 3;
  Estimator estimator(options);
  std::vector<FeatureReading> features;
  for (int k = 0; k < 5; ++k) features.push_back(Feature(4.0 + 2.0 * k, -0.8 + 0.4 * k));
  const ScanResult result = estimator.ProcessScan(Scan(100000, features), &rng_);
  EXPECT_EQ(result.objects.size(), 3u);
  EXPECT_EQ(result.counts.objects_refused, 2);
  EXPECT_EQ(estimator.counters().object_cap_hits, 2);
  EXPECT_NE(estimator.last_event().find("cap"), std::string::npos);
  ExpectHealthy(estimator);
}

// min_range_m 0 is allowed: a feature at (or next to) the sensor is then valid input. At a
// limited field of view its angular extent reaches the edge, and the edge-of-view bearing
// sigma (edge_of_view_sigma_m / range) must not become infinite there.
TEST_F(BadInputTest, AFeatureAtTheSensorKeepsTheStateFinite) {
  EstimatorOptions options;
  options.min_range_m = 0.0;
  options.field_of_view_rad = M_PI;
  Estimator estimator(options);
  FeatureReading at_sensor = Feature(0.0, 0.0);
  at_sensor.width_m = 0.3;
  FeatureReading next_to_sensor = Feature(1e-200, 0.1);
  next_to_sensor.width_m = 0.3;
  const ScanResult result =
      estimator.ProcessScan(Scan(100000, {at_sensor, next_to_sensor, Feature(5.0, 0.2)}), &rng_);
  ASSERT_TRUE(result.processed);
  EXPECT_EQ(result.counts.features_rejected, 0);
  EXPECT_EQ(result.counts.features_at_edge_of_view, 2);
  ExpectHealthy(estimator);
  estimator.ProcessScan(Scan(200000, {at_sensor, next_to_sensor, Feature(5.0, 0.2)}), &rng_);
  ExpectHealthy(estimator);
}

TEST_F(BadInputTest, OptionsAreChecked) {
  EXPECT_EQ(CheckEstimatorOptions(EstimatorOptions{}), "");
  EstimatorOptions o;
  o.gate_d2_chi2 = 1.0;
  EXPECT_NE(CheckEstimatorOptions(o), "");
  o = EstimatorOptions{};
  o.max_range_m = kNan;
  EXPECT_NE(CheckEstimatorOptions(o), "");
  o = EstimatorOptions{};
  o.ransac.success_probability = 1.0;
  EXPECT_NE(CheckEstimatorOptions(o), "");
  // Before: 0 was taken, and an estimator that may hold no object maps and tracks nothing.
  o = EstimatorOptions{};
  o.max_objects = 0;
  EXPECT_NE(CheckEstimatorOptions(o).find("max_objects = 0: must be"), std::string::npos);
  o.max_objects = 1;
  EXPECT_EQ(CheckEstimatorOptions(o), "");
  // 0 disables these two rules; a negative value is a mistake, not another way to disable them.
  o = EstimatorOptions{};
  o.classifier.still_velocity_chi2 = -1.0;
  EXPECT_NE(CheckEstimatorOptions(o), "");
  o = EstimatorOptions{};
  o.classifier.still_restart_variance_ratio = -0.5;
  EXPECT_NE(CheckEstimatorOptions(o), "");
  // A prediction bound below the gap limit would cut ordinary intervals short.
  o = EstimatorOptions{};
  o.max_prediction_s = 0.5 * o.max_time_gap_s;
  EXPECT_NE(CheckEstimatorOptions(o).find("max_prediction_s"), std::string::npos);
  o = EstimatorOptions{};
  o.time_jump_back_restart_s = 0.0;
  EXPECT_NE(CheckEstimatorOptions(o).find("time_jump_back_restart_s"), std::string::npos);
}

}  // namespace
}  // namespace slammtt
