// The smoother fed scan by scan (smoother/keyframe_smoother.h): keyframes, odometry and
// range-bearing factors from SmootherScanInput, removals, restarts, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/angle.h"
#include "common/options_schema.h"
#include "estimator/range_bearing_model.h"
#include "smoother/keyframe_smoother.h"
#include "geometry/pose2.h"
#include "tests/support/options_table.h"

namespace slammtt {
namespace {

constexpr int64_t kScanUs = 125000;  // 8 scans per second

// A robot driving a circle of radius 5 m at 0.1 m per scan through a ring of posts, seen by a
// laser 0.1 m ahead of the axle.
struct CircleWorld {
  SensorMount mount{0.1, 0.0, 0.0};
  std::vector<Eigen::Vector2d> posts;
  CircleWorld() {
    for (int k = 0; k < 12; ++k) {
      const double a = 2 * M_PI * k / 12;
      posts.emplace_back(8.0 * std::cos(a), 8.0 * std::sin(a) + 5.0);
    }
  }
  static Eigen::Vector3d TruePose(int scan) {
    const double a = 0.02 * scan;  // 0.1 m of arc per scan at radius 5
    return Eigen::Vector3d(5.0 * std::sin(a), 5.0 - 5.0 * std::cos(a), WrapAngle(a));
  }
  // Scan `scan`'s input: the true increment plus `heading_bias_rad` per scan, observations of
  // the posts within 6 m (ids 100 + k) without noise.
  SmootherScanInput Scan(int scan, double heading_bias_rad = 0.0) const {
    SmootherScanInput input;
    input.utime = 1000000 + scan * kScanUs;
    input.mount = mount;
    input.pose = TruePose(scan);
    input.pose_covariance = 1e-6 * Eigen::Matrix3d::Identity();
    input.continues = scan > 0;
    if (input.continues) {
      input.increment = PoseBetween(TruePose(scan - 1), TruePose(scan));
      input.increment(2) += heading_bias_rad;
      input.increment_covariance = Eigen::Vector3d(1e-4, 1e-6, 1e-4).asDiagonal();
    }
    for (size_t k = 0; k < posts.size(); ++k) {
      const Eigen::Vector2d z = PredictRangeBearing(TruePose(scan), posts[k], mount);
      if (z(0) > 6.0) continue;
      input.observations.push_back(StaticObservation{
          static_cast<int64_t>(100 + k), z,
          Eigen::Vector2d(0.01 * 0.01, 0.005 * 0.005).asDiagonal()});
    }
    return input;
  }
};

double PositionError(const SmoothedScan& s, int scan) {
  return (s.pose.head<2>() - CircleWorld::TruePose(scan).head<2>()).norm();
}

TEST(KeyframeSmootherTest, ExactInputGivesTheTruePoseAtEveryScan) {
  const CircleWorld world;
  KeyframeSmoother smoother(KeyframeSmootherOptions{});
  for (int scan = 0; scan < 60; ++scan) {
    const SmoothedScan s = smoother.AddScan(world.Scan(scan));
    ASSERT_TRUE(s.processed);
    EXPECT_TRUE(s.keyframe);
    ASSERT_TRUE(s.update.ok) << s.update.error;
    EXPECT_LT(PositionError(s, scan), 1e-6) << scan;
    EXPECT_GT(s.pose_covariance(0, 0), 0.0);
  }
  EXPECT_EQ(smoother.counters().keyframes, 60);
  EXPECT_EQ(smoother.counters().inputs_refused, 0) << smoother.last_error();
  const std::vector<SmoothedLandmark> landmarks = smoother.Landmarks();
  ASSERT_FALSE(landmarks.empty());
  for (const SmoothedLandmark& l : landmarks) {
    EXPECT_LT((l.position - world.posts[static_cast<size_t>(l.id - 100)]).norm(), 1e-6);
    EXPECT_GT(l.covariance(0, 0), 0.0);
  }
  EXPECT_EQ(smoother.Keyframes().size(), 60u);
}

TEST(KeyframeSmootherTest, TheLandmarksCorrectABiasedOdometry) {
  const CircleWorld world;
  KeyframeSmootherOptions options;
  options.optimize_every_keyframes = 20;
  KeyframeSmoother smoother(options);
  Eigen::Vector3d dead_reckoning = CircleWorld::TruePose(0);
  double worst_smoothed_m = 0.0;
  for (int scan = 0; scan < 150; ++scan) {
    const SmootherScanInput input = world.Scan(scan, 0.003);
    if (scan > 0) dead_reckoning = ComposePoses(dead_reckoning, input.increment);
    const SmoothedScan s = smoother.AddScan(input);
    worst_smoothed_m = std::max(worst_smoothed_m, PositionError(s, scan));
  }
  const double dead_reckoning_m =
      (dead_reckoning.head<2>() - CircleWorld::TruePose(149).head<2>()).norm();
  EXPECT_GT(dead_reckoning_m, 1.0);
  EXPECT_LT(worst_smoothed_m, 0.05);
  EXPECT_EQ(smoother.counters().batch_optimizations, 7);
}

TEST(KeyframeSmootherTest, TheKeyframeRuleComposesTheOdometryBetweenKeyframes) {
  const CircleWorld world;
  KeyframeSmootherOptions options;
  options.keyframe_distance_m = 0.45;  // every 5th scan (0.1 m each)
  KeyframeSmoother smoother(options);
  int64_t observations_between = 0;
  for (int scan = 0; scan < 41; ++scan) {
    const SmootherScanInput input = world.Scan(scan);
    const SmoothedScan s = smoother.AddScan(input);
    EXPECT_EQ(s.keyframe, scan % 5 == 0) << scan;
    if (!s.keyframe) observations_between += static_cast<int64_t>(input.observations.size());
    // Exact odometry: the pose between keyframes is exact too.
    EXPECT_LT(PositionError(s, scan), 1e-6) << scan;
  }
  EXPECT_EQ(smoother.counters().keyframes, 9);
  EXPECT_EQ(smoother.counters().observations_between_keyframes, observations_between);
  EXPECT_EQ(smoother.Keyframes().back().first, world.Scan(40).utime);
}

// The scans between keyframes (between_keyframe_observations): their sightings, fused per
// landmark through the motion since the keyframe (the laser's mount composed with it), are
// consistent with exact input (a wrong composition would bend the solution), add to what the
// solver uses, and shrink the landmarks' marginal covariances.
TEST(KeyframeSmootherTest, TheScansBetweenKeyframesAddTheirSightings) {
  const CircleWorld world;
  KeyframeSmootherOptions with;
  with.keyframe_distance_m = 0.45;  // every 5th scan
  KeyframeSmootherOptions without = with;
  without.between_keyframe_observations = false;
  KeyframeSmoother used(with);
  KeyframeSmoother left_out(without);
  for (int scan = 0; scan < 41; ++scan) {
    const SmoothedScan s = used.AddScan(world.Scan(scan));
    left_out.AddScan(world.Scan(scan));
    ASSERT_TRUE(s.processed);
    EXPECT_LT(PositionError(s, scan), 1e-6) << scan;
  }
  EXPECT_EQ(used.counters().inputs_refused, 0) << used.last_error();
  EXPECT_GT(used.counters().observations_used, 3 * left_out.counters().observations_used);
  const std::vector<SmoothedLandmark> a = used.Landmarks();
  const std::vector<SmoothedLandmark> b = left_out.Landmarks();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].id, b[k].id);
    EXPECT_LT((a[k].position - world.posts[static_cast<size_t>(a[k].id - 100)]).norm(), 1e-6);
    EXPECT_LT(a[k].covariance.trace(), b[k].covariance.trace()) << a[k].id;
  }
}

// With nothing but the prior and one increment, the second pose's marginal is the prior's
// plus the increment's covariance (heading: exactly; position: up to the 0.02 rad the increment
// turns): the scales must reach the odometry factor, each on its own component.
TEST(KeyframeSmootherTest, TheOdometryVarianceScalesWeighTheIncrementPerComponent) {
  const CircleWorld world;
  KeyframeSmootherOptions scaled_options;
  scaled_options.odometry_variance_scale_forward = 0.25;
  scaled_options.odometry_variance_scale_sideways = 9.0;
  scaled_options.odometry_variance_scale_heading = 0.04;
  KeyframeSmoother plain(KeyframeSmootherOptions{});
  KeyframeSmoother scaled(scaled_options);
  SmoothedScan last_plain, last_scaled;
  for (int scan = 0; scan < 2; ++scan) {
    SmootherScanInput input = world.Scan(scan);
    input.observations.clear();
    last_plain = plain.AddScan(input);
    last_scaled = scaled.AddScan(input);
  }
  const Eigen::Matrix3d increment = world.Scan(1).increment_covariance;
  const Eigen::Vector3d scales(0.25, 9.0, 0.04);
  for (int c = 0; c < 3; ++c) {
    const double change = last_scaled.pose_covariance(c, c) - last_plain.pose_covariance(c, c);
    const double expected = (scales(c) - 1.0) * increment(c, c);
    EXPECT_NEAR(change, expected, (c == 2 ? 1e-9 : 0.02) * std::abs(expected)) << c;
  }
}

TEST(KeyframeSmootherTest, TentativeSightingsJoinWhenTheObjectBecomesALandmark) {
  const CircleWorld world;
  KeyframeSmoother held(KeyframeSmootherOptions{});
  KeyframeSmoother direct(KeyframeSmootherOptions{});
  // Held: tentative sightings of posts that are not landmarks yet (not seen at scan 0).
  int64_t tentative_new = 0;
  std::vector<int64_t> at_start;
  for (const StaticObservation& o : world.Scan(0).observations) at_start.push_back(o.landmark_id);
  for (int scan = 0; scan < 30; ++scan) {
    SmootherScanInput input = world.Scan(scan, 0.003);
    direct.AddScan(input);
    // The first 20 scans' sightings of every post are tentative.
    for (StaticObservation& o : input.observations) {
      o.tentative = scan < 20 && scan > 0;
      const bool known =
          std::find(at_start.begin(), at_start.end(), o.landmark_id) != at_start.end();
      tentative_new += o.tentative && !known ? 1 : 0;
    }
    held.AddScan(input);
  }
  EXPECT_GT(tentative_new, 0);
  EXPECT_EQ(held.counters().observations_held, tentative_new);
  // Every held sighting of a post seen again later is used: the same problem as without holding.
  EXPECT_EQ(held.counters().observations_used, direct.counters().observations_used);
  const auto a = held.Keyframes();
  const auto b = direct.Keyframes();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LT((a.back().second - b.back().second).norm(), 1e-3);
  // A removal drops what is held.
  SmootherScanInput input = world.Scan(30);
  for (StaticObservation& o : input.observations) o.tentative = true;
  input.observations.front().landmark_id = 777;
  held.AddScan(input);
  SmootherScanInput removal = world.Scan(31);
  removal.observations.clear();
  removal.removed_landmark_ids = {777};
  held.AddScan(removal);
  EXPECT_EQ(held.counters().held_observations_dropped, 1);
}

TEST(KeyframeSmootherTest, ARemovedLandmarkLeavesAndMayComeBack) {
  const CircleWorld world;
  KeyframeSmoother smoother(KeyframeSmootherOptions{});
  for (int scan = 0; scan < 10; ++scan) smoother.AddScan(world.Scan(scan));
  const int64_t seen = world.Scan(9).observations.front().landmark_id;
  SmootherScanInput removal = world.Scan(10);
  removal.removed_landmark_ids = {seen, 999};  // 999: never in the problem, no error
  removal.observations.erase(removal.observations.begin());
  const SmoothedScan s = smoother.AddScan(removal);
  EXPECT_TRUE(s.update.ok) << s.update.error;
  EXPECT_EQ(smoother.counters().landmarks_removed, 1);
  EXPECT_EQ(smoother.counters().inputs_refused, 0) << smoother.last_error();
  for (const SmoothedLandmark& l : smoother.Landmarks()) EXPECT_NE(l.id, seen);
  // Static again: a new variable under the same id.
  const SmoothedScan back = smoother.AddScan(world.Scan(11));
  EXPECT_TRUE(back.update.ok) << back.update.error;
  bool found = false;
  for (const SmoothedLandmark& l : smoother.Landmarks()) found = found || l.id == seen;
  EXPECT_TRUE(found);
  EXPECT_LT(PositionError(back, 11), 1e-6);
}

TEST(KeyframeSmootherTest, AScanThatDoesNotContinueStartsANewProblem) {
  const CircleWorld world;
  KeyframeSmoother smoother(KeyframeSmootherOptions{});
  for (int scan = 0; scan < 10; ++scan) smoother.AddScan(world.Scan(scan));
  SmootherScanInput restart = world.Scan(0);
  restart.utime = world.Scan(9).utime + kScanUs;
  restart.pose = Eigen::Vector3d(1, 2, 0.5);
  restart.observations.clear();
  const SmoothedScan s = smoother.AddScan(restart);
  EXPECT_TRUE(s.keyframe);
  EXPECT_LT((s.pose - restart.pose).norm(), 1e-9);
  EXPECT_EQ(smoother.counters().restarts, 1);
  EXPECT_EQ(smoother.Keyframes().size(), 1u);
  EXPECT_TRUE(smoother.Landmarks().empty());
}

TEST(KeyframeSmootherTest, BadInputIsRefusedCountedAndTheRestOfTheScanIsUsed) {
  const CircleWorld world;
  KeyframeSmoother smoother(KeyframeSmootherOptions{});
  smoother.AddScan(world.Scan(0));
  SmootherScanInput bad = world.Scan(1);
  ASSERT_GE(bad.observations.size(), 2u);
  bad.observations[0].range_bearing(0) = std::nan("");
  bad.observations[0].landmark_id = 555;  // a new landmark that cannot be placed
  bad.observations[1].covariance = -Eigen::Matrix2d::Identity();
  const SmoothedScan s = smoother.AddScan(bad);
  EXPECT_TRUE(s.update.ok) << s.update.error;
  EXPECT_EQ(smoother.counters().inputs_refused, 2);
  EXPECT_FALSE(smoother.last_error().empty());
  EXPECT_EQ(smoother.counters().observations_used,
            static_cast<int64_t>(world.Scan(0).observations.size() + bad.observations.size() - 2));
  EXPECT_LT(PositionError(s, 1), 1e-6);
  // An older scan is dropped.
  EXPECT_FALSE(smoother.AddScan(world.Scan(1)).processed);
  EXPECT_EQ(smoother.counters().scans_out_of_order, 1);
}

TEST(KeyframeSmootherTest, UnusableOptionsAreRefusedByTheConstructor) {
  KeyframeSmootherOptions options;
  options.odometry_min_sigma_m = 0.0;
  EXPECT_THROW(KeyframeSmoother{options}, std::invalid_argument);
  EXPECT_NE(CheckKeyframeSmootherOptions(options).find("odometry_min_sigma_m"),
            std::string::npos);
  options = KeyframeSmootherOptions{};
  options.odometry_variance_scale_heading = 0.0;
  EXPECT_NE(CheckKeyframeSmootherOptions(options).find("odometry_variance_scale_heading"),
            std::string::npos);
  options = KeyframeSmootherOptions{};
  options.keyframe_distance_m = -1.0;
  EXPECT_NE(CheckKeyframeSmootherOptions(options).find("keyframe_distance_m"), std::string::npos);
  // The solver's rule beyond its ranges (CheckSmootherOptions), named with its group.
  options = KeyframeSmootherOptions{};
  options.solver.max_lambda = options.solver.initial_lambda / 2;
  EXPECT_THROW(KeyframeSmoother{options}, std::invalid_argument);
  EXPECT_EQ(CheckKeyframeSmootherOptions(options),
            "solver: max_lambda must be >= initial_lambda");
  EXPECT_EQ(CheckKeyframeSmootherOptions(KeyframeSmootherOptions{}), "");
}

TEST(KeyframeSmootherTest, SameInputGivesTheSameBytes) {
  const CircleWorld world;
  auto run = [&] {
    KeyframeSmootherOptions options;
    options.optimize_every_keyframes = 7;
    KeyframeSmoother smoother(options);
    std::vector<double> numbers;
    for (int scan = 0; scan < 40; ++scan) {
      const SmoothedScan s = smoother.AddScan(world.Scan(scan, 0.002));
      numbers.insert(numbers.end(), s.pose.data(), s.pose.data() + 3);
      numbers.insert(numbers.end(), s.pose_covariance.data(), s.pose_covariance.data() + 9);
    }
    for (const SmoothedLandmark& l : smoother.Landmarks()) {
      numbers.push_back(l.position(0));
      numbers.push_back(l.covariance(1, 1));
    }
    return numbers;
  };
  const std::vector<double> a = run();
  const std::vector<double> b = run();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

// docs/smoother.md carries the `smoother:` section's table the schema makes (what
// `slammtt-smoother --options-table` prints), the solver's keys included.
TEST(KeyframeSmootherOptionsTest, TheSectionsOptionsTableIsDocumented) {
  KeyframeSmootherOptions defaults;
  OptionsMarkdownTable table;
  VisitKeyframeSmootherOptions(&table, &defaults);
  ASSERT_NE(table.Table().find("| `solver_pose_update` |"), std::string::npos);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/smoother.md");
  ASSERT_FALSE(docs.empty()) << "docs/smoother.md is part of the checkout";
  EXPECT_NE(docs.find(table.Table()), std::string::npos)
      << "docs/smoother.md, Options (`smoother:` section): replace the table by "
         "`slammtt-smoother --options-table`";
}

}  // namespace
}  // namespace slammtt
