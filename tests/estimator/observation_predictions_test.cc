// Predicted observations computed once per state (estimator/observation_predictions.h), and
// how many times a scan of the estimator computes them.
#include "estimator/observation_predictions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "estimator/ekf_update.h"
#include "estimator/estimator.h"
#include "estimator/testing/point_world.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

void ExpectSamePredictions(const std::vector<ObjectPrediction>& a,
                           const std::vector<ObjectPrediction>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t j = 0; j < a.size(); ++j) {
    EXPECT_EQ(a[j].valid, b[j].valid);
    EXPECT_EQ(a[j].range_bearing, b[j].range_bearing);
    EXPECT_EQ(a[j].jacobian_robot, b[j].jacobian_robot);
    EXPECT_EQ(a[j].jacobian_position, b[j].jacobian_position);
    EXPECT_EQ(a[j].hph, b[j].hph);
  }
}

TEST(ObservationPredictionsTest, OneComputationPerStateBitForBit) {
  StepScene scene;
  scene.AddLandmark({5.0, 1.0}, 0.1);
  scene.AddMover({2.0, -3.0}, 0.3, {1.0, 0.0}, 0.5);
  ObservationPredictions predicted(scene.options.sensor);
  ExpectSamePredictions(predicted.At(scene.state), scene.Predictions());
  predicted.At(scene.state);
  const SlamState& unchanged = scene.state;
  predicted.At(unchanged);
  EXPECT_EQ(predicted.computations(), 1) << "same state: no recomputation";
  // Reading records does not count as a change.
  scene.state.object(0).record.hits += 1;
  predicted.At(scene.state);
  EXPECT_EQ(predicted.computations(), 1);
  // An update changes the state: computed again, equal to a fresh computation.
  scene.Measure({5.1, 1.0});
  ApplyObservations({{0, scene.measurements[0]}}, scene.options.sensor, 1e9, 1, &scene.state);
  ExpectSamePredictions(predicted.At(scene.state), scene.Predictions());
  EXPECT_EQ(predicted.computations(), 2);
  // So does any mutable view of the covariance or the mean, and a new object.
  scene.state.covariance()(0, 0) += 1e-4;
  ExpectSamePredictions(predicted.At(scene.state), scene.Predictions());
  scene.state.mean()(1) += 0.01;
  ExpectSamePredictions(predicted.At(scene.state), scene.Predictions());
  scene.AddLandmark({-3.0, 0.0}, 0.1);
  ExpectSamePredictions(predicted.At(scene.state), scene.Predictions());
  EXPECT_EQ(predicted.computations(), 5);
  // Another state object (even a copy with the same revision) is predicted afresh.
  SlamState copy = scene.state;
  copy.mean()(0) += 1.0;
  ExpectSamePredictions(predicted.At(copy), PredictObservations(copy, scene.options.sensor));
  EXPECT_EQ(predicted.computations(), 6);
}

// A scan of the s1 setting (180 degrees, 30 m, people and landmarks) through the estimator: the
// predictions are computed at most once per state the scan passes through, and twice in a scan
// where only level 1 changes the state (the predicted state, the state after level 1).
TEST(ObservationPredictionsTest, TheEstimatorPredictsOncePerStateNotOncePerStep) {
  // bench_estimator's BM_TypicalScan world: 60 landmarks around a robot at 1.5 m/s, 5 walkers.
  testing::PointWorldOptions world_options;
  world_options.sensor.forward_m = 0.1;
  std::vector<testing::WorldObject> objects = testing::CrowdedScene(60, 0, 40.0, 7);
  for (int k = 0; k < 5; ++k) {
    testing::WorldObject mover;
    mover.id = 1000 + k;
    mover.mover = true;
    mover.start_m = Eigen::Vector2d(8.0 + 3.0 * k, -6.0 + 2.5 * k);
    mover.segments.push_back({1e18, Eigen::Vector2d(-0.3 + 0.15 * k, 0.6 - 0.3 * k)});
    objects.push_back(mover);
  }
  testing::PointWorld world(
      world_options, [](double t) { return Eigen::Vector2d(1.5, 0.2 * std::sin(0.1 * t)); },
      objects);
  EstimatorOptions options;
  options.sensor = world_options.sensor;
  options.field_of_view_rad = world_options.field_of_view_rad;
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  int level1_only_scans = 0;
  int total = 0;
  int scans = 0;
  for (int k = 0; k < 200; ++k) {
    const testing::WorldFrame frame = world.Next();
    for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
    const ScanResult result = estimator.ProcessScan(frame.scan, &rng);
    const StepCounts& c = result.counts;
    // The states a scan can pass through: predicted, after level 1, after level 2, after the
    // manoeuvres, after level 3, after the class changes (a change to MOVING and a take-over
    // of a lost identity drop the object's stationary anchor: SlamState::RemoveAnchor).
    const int states = 1 + (c.level1_updates > 0) + (c.level2_updates > 0) + (c.manoeuvres > 0) +
                       (c.level3_updates > 0) +
                       (c.became_static + c.started_moving + c.became_moving + c.reacquired > 0
                            ? 1
                            : 0);
    EXPECT_LE(c.observation_predictions, states) << "scan " << k;
    EXPECT_GE(c.observation_predictions, 1);
    if (c.level1_updates > 0 && c.level2_updates == 0 && c.level3_updates == 0 &&
        c.manoeuvres == 0 && c.became_static == 0 && c.started_moving == 0 &&
        c.became_moving == 0 && c.reacquired == 0) {
      EXPECT_EQ(c.observation_predictions, 2) << "scan " << k;
      ++level1_only_scans;
    }
    total += c.observation_predictions;
    ++scans;
  }
  EXPECT_GT(level1_only_scans, 100);
  std::cout << "predictions computed per scan: " << static_cast<double>(total) / scans
            << " (mean over " << scans << " scans)\n";
}

}  // namespace
}  // namespace slammtt
