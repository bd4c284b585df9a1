// The parts that keep a crowded scan cheap: the bearing lookup of the gating (same pairs as
// trying every pair), the per-scan budget of static-landmark updates (at most K, every landmark
// in turn, movers always, the filter stays consistent) and the state's tiled mirror and
// compaction on large states.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <set>

#include "common/angle.h"
#include "estimator/estimator.h"
#include "estimator/gating.h"
#include "estimator/testing/point_world.h"
#include "estimator/update_budget.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::WorldFrame;
using testing::WorldObject;

// The definition of GatePairs: every pair, in order.
std::vector<Candidate> EveryPair(const std::vector<PointMeasurement>& measurements,
                                 const std::vector<ObjectPrediction>& predictions, double gate) {
  std::vector<Candidate> pairs;
  for (size_t i = 0; i < measurements.size(); ++i) {
    for (size_t j = 0; j < predictions.size(); ++j) {
      const double nis = NormalizedInnovationSquared(measurements[i], predictions[j], gate);
      if (nis < gate) pairs.push_back({static_cast<int>(i), static_cast<int>(j), nis});
    }
  }
  return pairs;
}

TEST(ObjectsThatMayUpdateTest, TheKLeastRecentlyUpdatedLandmarksWithAPairAndEveryMover) {
  testing::StepScene scene;
  const int64_t updated_at[] = {5, 3, 3, 9, 1};
  for (int k = 0; k < 5; ++k) {
    scene.AddLandmark({5.0, 1.0 * k}, 0.1);
    scene.state.object(k).record.last_update_utime = updated_at[k];
  }
  const int mover = scene.AddMover({-5.0, 0.0}, 0.1, {0.0, 0.0}, 0.1);
  // Landmark 4 (the stalest) has no pair this scan; the mover has one.
  const std::vector<Candidate> gated = {{0, 0, 1.0}, {1, 1, 1.0}, {2, 2, 1.0}, {3, 3, 1.0},
                                        {4, mover, 1.0}, {5, 1, 2.0}};
  // Budget 2 among landmarks 0-3: the least recently updated are 1 and 2 (tie at 3: both).
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 2, 0),
            (std::vector<uint8_t>{0, 1, 1, 0, 1, 1}));
  // A tie at the cut goes to the lower index.
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 1, 0),
            (std::vector<uint8_t>{0, 1, 0, 0, 1, 1}));
  // No limit, or a budget as large as the competitors.
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 0, 0), std::vector<uint8_t>(6, 1));
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 4, 0), std::vector<uint8_t>(6, 1));
}

TEST(ObjectsThatMayUpdateTest, TheMLeastRecentlyUpdatedMoversWithAPair) {
  testing::StepScene scene;
  const int64_t updated_at[] = {7, 2, 4, 2};
  for (int k = 0; k < 4; ++k) {
    const int mover = scene.AddMover({5.0, 1.0 * k}, 0.1, {0.0, 0.0}, 0.1);
    scene.state.object(mover).record.last_update_utime = updated_at[k];
  }
  scene.AddLandmark({-5.0, 0.0}, 0.1);
  const std::vector<Candidate> gated = {{0, 0, 1.0}, {1, 1, 1.0}, {2, 2, 1.0}, {3, 3, 1.0},
                                        {4, 4, 1.0}};
  // Budget 2 among the movers: 1 and 3 (updated at 2); the landmark is in the other budget.
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 32, 2),
            (std::vector<uint8_t>{0, 1, 0, 1, 1}));
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 32, 3),
            (std::vector<uint8_t>{0, 1, 1, 1, 1}));
  EXPECT_EQ(ObjectsThatMayUpdate(scene.state, gated, 32, 0), std::vector<uint8_t>(5, 1));
}

TEST(GatingTest, BearingLookupFindsExactlyThePairsOfTheFullLoop) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<ObjectPrediction> predictions(200);
    for (size_t j = 0; j < predictions.size(); ++j) {
      ObjectPrediction& p = predictions[j];
      p.valid = j % 37 != 5;  // a few objects at the sensor
      p.range_bearing = Eigen::Vector2d(1.0 + 29.0 * unit(rng), M_PI * (2.0 * unit(rng) - 1.0));
      // Crowd the seam at +-pi, where the lookup wraps.
      if (j % 5 == 0) p.range_bearing(1) = (j % 10 == 0 ? 1.0 : -1.0) * (M_PI - 0.05 * unit(rng));
      const double bearing_var = j % 23 == 0 ? 0.5 * unit(rng) : 1e-4 * unit(rng);  // some wide
      const double range_var = 0.5 * unit(rng);
      p.hph << range_var, 0.3 * std::sqrt(range_var * bearing_var),
          0.3 * std::sqrt(range_var * bearing_var), bearing_var;
    }
    std::vector<PointMeasurement> measurements;
    for (const ObjectPrediction& p : predictions) {
      if (unit(rng) < 0.2) continue;
      PointMeasurement z;
      z.range_bearing = p.range_bearing + Eigen::Vector2d(0.4 * (unit(rng) - 0.5),
                                                          0.2 * (unit(rng) - 0.5));
      z.range_bearing(1) = WrapAngle(z.range_bearing(1));
      z.covariance = Eigen::Vector2d(0.04, std::pow(0.035 * (0.5 + unit(rng)), 2)).asDiagonal();
      measurements.push_back(z);
    }
    ASSERT_GT(measurements.size() * predictions.size(), kGatingBruteForcePairs);
    for (double gate : {9.21, 20.0, 200.0}) {
      const std::vector<Candidate> expected = EveryPair(measurements, predictions, gate);
      const std::vector<Candidate> found = GatePairs(measurements, predictions, gate);
      ASSERT_EQ(found.size(), expected.size()) << "trial " << trial << " gate " << gate;
      for (size_t k = 0; k < found.size(); ++k) {
        EXPECT_EQ(found[k].measurement, expected[k].measurement);
        EXPECT_EQ(found[k].object, expected[k].object);
        EXPECT_EQ(found[k].nis, expected[k].nis);
      }
    }
  }
}

// 40 static points all around, far enough apart that every one is associated at level 1.
std::vector<WorldObject> Ring(int count) {
  std::vector<WorldObject> objects;
  for (int k = 0; k < count; ++k) {
    const double angle = 2.0 * M_PI * k / count;
    const double radius = 8.0 + 4.0 * (k % 3);
    objects.push_back({k + 1, radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)), {},
                       false});
  }
  return objects;
}

EstimatorOptions WorldOptions(const PointWorldOptions& world) {
  EstimatorOptions options;
  options.field_of_view_rad = world.field_of_view_rad;
  options.odometry_noise.distance_var_per_m =
      world.wheel_noise_per_sqrt_m * world.wheel_noise_per_sqrt_m;
  options.odometry_noise.rotation_var_per_m =
      world.turn_noise_per_sqrt_m * world.turn_noise_per_sqrt_m;
  options.odometry_noise.rotation_var_per_rad = 0.0;
  return options;
}

Eigen::Vector2d Arc(double) { return Eigen::Vector2d(0.3, 0.05); }

TEST(UpdateBudgetTest, AtMostKLandmarksUpdateAndEveryOneTakesItsTurn) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  PointWorld world(world_options, Arc, Ring(40));
  EstimatorOptions options = WorldOptions(world_options);
  constexpr int kBudget = 10;
  options.max_static_updates_per_scan = kBudget;
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  const int64_t period_us = 125000;
  int checked_scans = 0;
  bool all_static = false;  // before the scan: every one of the 40 is a classified landmark
  for (int k = 0; k < 20 * 8; ++k) {
    const WorldFrame frame = world.Next();
    for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
    const ScanResult result = estimator.ProcessScan(frame.scan, &rng);
    ASSERT_TRUE(result.processed);
    const SlamState& state = estimator.state();
    const bool checked = all_static;
    all_static = state.num_objects() == 40;
    for (const StateObject& o : state.objects()) all_static = all_static && !o.has_velocity();
    if (!checked) continue;
    // A static world: K updates, the other associated landmarks skipped.
    int associated = 0;
    for (const StateObject& o : state.objects()) {
      associated += o.record.last_seen_utime == frame.utime ? 1 : 0;
    }
    const int updates =
        result.counts.level1_updates + result.counts.level2_updates + result.counts.level3_updates;
    EXPECT_EQ(updates, kBudget) << "scan " << k;
    EXPECT_EQ(updates + result.counts.static_updates_skipped, associated) << "scan " << k;
    EXPECT_GE(associated, 38) << "scan " << k;
    EXPECT_EQ(result.counts.new_objects, 0);
    // Least recently updated first: once the budget has cycled, none of the landmarks seen now
    // waited more than about 40 / K scans (one more when some were missed meanwhile).
    if (++checked_scans > 40 / kBudget) {
      for (const StateObject& o : state.objects()) {
        if (o.record.last_seen_utime != frame.utime) continue;
        EXPECT_LE(frame.utime - o.record.last_update_utime, (40 / kBudget) * period_us)
            << "object " << o.record.id << " at scan " << k;
      }
    }
  }
  EXPECT_GT(checked_scans, 80) << "the landmarks were not all static by mid-run";
  EXPECT_GE(estimator.counters().static_updates_skipped, 30 * checked_scans);
}

TEST(UpdateBudgetTest, MoversAndUndecidedObjectsAlwaysUpdate) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  std::vector<WorldObject> objects = Ring(30);
  for (int k = 0; k < 4; ++k) {
    objects.push_back({100 + k, Eigen::Vector2d(3.0 + 1.5 * k, -4.0 + 2.5 * k),
                       {{1e18, Eigen::Vector2d(0.6 - 0.3 * k, 0.5)}}, true});
  }
  PointWorld world(world_options, Arc, objects);
  EstimatorOptions options = WorldOptions(world_options);
  options.max_static_updates_per_scan = 3;
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  int checked = 0;
  for (int k = 0; k < 12 * 8; ++k) {
    const WorldFrame frame = world.Next();
    for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
    const ScanResult result = estimator.ProcessScan(frame.scan, &rng);
    // Objects that had velocity states before this scan's classification: the ones that have
    // them now (none started to move here, checked below) and the ones that just became static.
    EXPECT_EQ(result.counts.started_moving, 0);
    int velocity_objects_seen = result.counts.became_static;
    for (const StateObject& o : estimator.state().objects()) {
      if (!o.has_velocity() || o.record.last_seen_utime != frame.utime) continue;
      if (o.record.first_seen_utime == frame.utime) continue;  // created by this scan
      EXPECT_EQ(o.record.last_update_utime, frame.utime) << "object " << o.record.id;
      ++velocity_objects_seen;
      ++checked;
    }
    const int updates =
        result.counts.level1_updates + result.counts.level2_updates + result.counts.level3_updates;
    EXPECT_LE(updates, 3 + velocity_objects_seen) << "scan " << k;
  }
  EXPECT_GT(checked, 4 * 60);
  int moving = 0;
  for (const StateObject& o : estimator.state().objects()) {
    moving += o.record.object_class == ObjectClass::kMoving ? 1 : 0;
  }
  EXPECT_EQ(moving, 4);
}

// Leaving measurements out on a rule that does not look at their values only loses
// information: the robot's error stays within what its covariance says (normalized estimation
// error squared of the position, 2 dof, mean 2 for a consistent filter), budget or not.
TEST(UpdateBudgetTest, BudgetedFilterStaysConsistent) {
  for (int budget : {0, 4}) {
    SCOPED_TRACE("budget " + std::to_string(budget));
    PointWorldOptions world_options;
    world_options.field_of_view_rad = 2.0 * M_PI;
    PointWorld world(world_options, Arc, Ring(40));
    EstimatorOptions options = WorldOptions(world_options);
    options.max_static_updates_per_scan = budget;
    Estimator estimator(options);
    std::mt19937_64 rng(1);
    double nees_sum = 0.0;
    int scans = 0;
    for (int k = 0; k < 60 * 8; ++k) {
      const WorldFrame frame = world.Next();
      for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
      const ScanResult result = estimator.ProcessScan(frame.scan, &rng);
      if (k < 8 * 8) continue;
      const Eigen::Vector2d error = result.pose.head<2>() - frame.true_pose.head<2>();
      nees_sum += error.dot(result.pose_covariance.topLeftCorner<2, 2>().ldlt().solve(error));
      ++scans;
    }
    const double mean_nees = nees_sum / scans;
    std::cout << "budget " << budget << ": mean robot position NEES " << mean_nees << "\n";
    EXPECT_LT(mean_nees, 6.0);
  }
}

// A state large enough for several tiles of the mirror and a compaction across them.
TEST(SlamStateLargeTest, RemovingObjectsAndDowndatingMatchDenseReferences) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> normal(0.0, 1.0);
  SlamState state(Eigen::Vector3d(0.1, -0.2, 0.3), 0.01 * Eigen::Matrix3d::Identity());
  for (int k = 0; k < 90; ++k) {
    Eigen::Matrix<double, 2, 3> g;
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) g(r, c) = normal(rng);
    }
    ObjectRecord record;
    record.id = k + 1;
    const int j = state.AddObject(5.0 * Eigen::Vector2d(normal(rng), normal(rng)), g,
                                  0.04 * Eigen::Matrix2d::Identity(), record);
    if (k % 3 == 0) state.AddVelocity(j, Eigen::Vector2d(0.1, 0.2), Eigen::Matrix2d::Identity());
  }
  const int n = state.dim();
  ASSERT_GT(n, 200);
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) a(r, c) += 0.02 * normal(rng);
  }
  const Eigen::MatrixXd mixed = a * state.covariance() * a.transpose();
  state.covariance() = 0.5 * (mixed + mixed.transpose());
  // Downdate: P - V V^T, symmetric to the last bit.
  Eigen::MatrixXd v_transposed(6, n);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < n; ++c) v_transposed(r, c) = 0.01 * normal(rng);
  }
  const Eigen::MatrixXd expected =
      Eigen::MatrixXd(state.covariance()) - v_transposed.transpose() * v_transposed;
  state.SubtractSymmetricProduct(v_transposed);
  EXPECT_EQ(state.covariance(), state.covariance().transpose());
  EXPECT_LT((state.covariance() - expected).cwiseAbs().maxCoeff(), 1e-12);
  // Compaction: removing objects keeps exactly the other rows and columns.
  const Eigen::MatrixXd p = state.covariance();
  const Eigen::VectorXd x = state.mean();
  const std::vector<int> removed = {0, 7, 8, 40, 41, 42, 89};
  std::set<int> removed_states;
  for (int k : removed) {
    const StateObject& o = state.object(k);
    removed_states.insert({o.position_index, o.position_index + 1});
    if (o.has_velocity()) removed_states.insert({o.velocity_index, o.velocity_index + 1});
  }
  std::vector<int> kept;
  for (int i = 0; i < n; ++i) {
    if (removed_states.count(i) == 0) kept.push_back(i);
  }
  state.RemoveObjects(removed);
  ASSERT_EQ(state.dim(), static_cast<int>(kept.size()));
  ASSERT_EQ(state.num_objects(), 90 - static_cast<int>(removed.size()));
  for (int r = 0; r < state.dim(); ++r) {
    ASSERT_EQ(state.mean()(r), x(kept[static_cast<size_t>(r)]));
    for (int c = 0; c < state.dim(); ++c) {
      ASSERT_EQ(state.covariance()(r, c),
                p(kept[static_cast<size_t>(r)], kept[static_cast<size_t>(c)]))
          << r << ", " << c;
    }
  }
}

}  // namespace
}  // namespace slammtt
