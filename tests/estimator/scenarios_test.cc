// Small hand-made worlds: the estimator must map the static points, track the movers, label
// each correctly and in time, and reclassify objects that stop or start to move.
#include <gtest/gtest.h>

#include <iostream>

#include "tests/estimator/scenario_runner.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::RunScenario;
using testing::RunSummary;
using testing::WorldObject;

// The estimator's defaults, with the odometry noise of the point world (its wheel and turn
// noise per sqrt(m), as variances per m).
EstimatorOptions DefaultOptions() {
  EstimatorOptions options;
  const PointWorldOptions world;
  options.odometry_noise.distance_var_per_m = world.wheel_noise_per_sqrt_m * world.wheel_noise_per_sqrt_m;
  options.odometry_noise.rotation_var_per_m = world.turn_noise_per_sqrt_m * world.turn_noise_per_sqrt_m;
  options.odometry_noise.rotation_var_per_rad = 0.0;
  return options;
}

Eigen::Vector2d SlowArc(double t) { return Eigen::Vector2d(0.3, 0.05 * std::sin(0.2 * t)); }

TEST(ScenariosTest, TwoLandmarksAndAWalker) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  std::vector<WorldObject> objects(3);
  objects[0] = {1, {6.0, 2.0}, {}, false};
  objects[1] = {2, {7.0, -2.5}, {}, false};
  objects[2] = {3, {9.0, 5.0}, {{1e18, {-0.2, -0.9}}}, true};
  PointWorld world(world_options, SlowArc, objects);
  EstimatorOptions options = DefaultOptions();
  Estimator estimator(options);
  const RunSummary summary = RunScenario(&world, &estimator, 12 * 8, 1);
  std::cout << testing::Describe(summary);
  const auto& walker = summary.objects.at(3);
  EXPECT_GE(walker.first_moving_s, 0.0);
  EXPECT_LE(walker.first_moving_s - walker.first_seen_s, 2.0);
  EXPECT_EQ(walker.id_switches, 0);
  EXPECT_LT(walker.first_static_s, 0.0) << "the walker was labelled static";
  EXPECT_GE(summary.objects.at(1).first_static_s, 0.0);
  EXPECT_GE(summary.objects.at(2).first_static_s, 0.0);
  EXPECT_LT(summary.objects.at(1).first_moving_s, 0.0);
  EXPECT_EQ(summary.movers_in_final_map, 0);
  EXPECT_LT(summary.ate_rmse_m, 0.3);
}

// A person stands for 6 s (becomes a static landmark), then walks away at 1 m/s (must become
// a mover again), seen from a robot that also sees two walls' corners.
TEST(ScenariosTest, PersonWhoStandsThenWalks) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  std::vector<WorldObject> objects(3);
  objects[0] = {1, {6.0, 3.0}, {}, false};
  objects[1] = {2, {7.0, -3.0}, {}, false};
  objects[2] = {3, {5.0, 0.5}, {{6.0, {0.0, 0.0}}, {1e18, {0.6, 0.8}}}, true};
  PointWorld world(world_options, [](double) { return Eigen::Vector2d(0.1, 0.0); }, objects);
  Estimator estimator(DefaultOptions());
  const RunSummary summary = RunScenario(&world, &estimator, 12 * 8, 2);
  std::cout << testing::Describe(summary);
  const auto& person = summary.objects.at(3);
  EXPECT_GE(person.first_static_s, 0.0) << "standing person never labelled static";
  EXPECT_LT(person.first_static_s, 6.0);
  EXPECT_GT(person.first_moving_s, 6.0) << "labelled moving while standing";
  const double delay = person.first_moving_s - 6.0;
  std::cout << "static -> moving reclassification delay: " << delay << " s\n";
  ::testing::Test::RecordProperty("static_to_moving_delay_s", std::to_string(delay));
  EXPECT_LE(delay, 2.0);
  EXPECT_EQ(person.id_switches, 0);
  EXPECT_EQ(summary.movers_in_final_map, 0);
}

// A walker crosses the scene at 1 m/s and stops for good at t = 5 s: it must become a static
// landmark (velocity states removed), and stay tracked without an identity switch.
TEST(ScenariosTest, WalkerWhoStops) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  std::vector<WorldObject> objects(3);
  objects[0] = {1, {6.0, 3.0}, {}, false};
  objects[1] = {2, {7.0, -3.0}, {}, false};
  objects[2] = {3, {4.0, -3.0}, {{5.0, {0.0, 1.0}}}, true};
  PointWorld world(world_options, [](double) { return Eigen::Vector2d(0.1, 0.0); }, objects);
  Estimator estimator(DefaultOptions());
  const RunSummary summary = RunScenario(&world, &estimator, 14 * 8, 3);
  std::cout << testing::Describe(summary);
  const auto& walker = summary.objects.at(3);
  EXPECT_GE(walker.first_moving_s, 0.0);
  EXPECT_LE(walker.first_moving_s - walker.first_seen_s, 2.0);
  EXPECT_GT(walker.first_static_s, 5.0);
  const double delay = walker.first_static_s - 5.0;
  std::cout << "moving -> static reclassification delay: " << delay << " s\n";
  ::testing::Test::RecordProperty("moving_to_static_delay_s", std::to_string(delay));
  EXPECT_LE(delay, 5.0);
  EXPECT_GE(walker.last_static_s, 13.5) << "did not stay static";
  EXPECT_EQ(walker.id_switches, 0);
}

// Two walkers cross each other's path (at t = 4 s they are 0.4 m apart) while the robot moves:
// the association is ambiguous around the crossing and RANSAC must resolve it.
TEST(ScenariosTest, CrossingWalkersKeepTheirIdentities) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    PointWorldOptions world_options;
    world_options.seed = seed;
    std::vector<WorldObject> objects(4);
    objects[0] = {1, {9.0, 4.0}, {}, false};
    objects[1] = {2, {10.0, -4.0}, {}, false};
    objects[2] = {3, {6.0, -3.0}, {{1e18, {0.5, 0.8}}}, true};
    objects[3] = {4, {8.0, -3.4}, {{1e18, {0.0, 0.8}}}, true};
    PointWorld world(world_options, SlowArc, objects);
    Estimator estimator(DefaultOptions());
    const RunSummary summary = RunScenario(&world, &estimator, 9 * 8, seed);
    SCOPED_TRACE(testing::Describe(summary));
    EXPECT_EQ(summary.objects.at(3).id_switches, 0) << "seed " << seed;
    EXPECT_EQ(summary.objects.at(4).id_switches, 0) << "seed " << seed;
    EXPECT_GE(summary.objects.at(3).first_moving_s, 0.0);
    EXPECT_GE(summary.objects.at(4).first_moving_s, 0.0);
    EXPECT_EQ(summary.movers_in_final_map, 0);
  }
}

// Baseline (a), EKF-SLAM assuming a static world, shows the paper's failure (Fig. 5): movers
// end up in the static map.
TEST(ScenariosTest, StaticWorldBaselineMapsMoversAsStatic) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  std::vector<WorldObject> objects(3);
  objects[0] = {1, {6.0, 2.0}, {}, false};
  objects[1] = {2, {7.0, -2.5}, {}, false};
  objects[2] = {3, {9.0, 5.0}, {{1e18, {-0.2, -0.9}}}, true};
  PointWorld world(world_options, SlowArc, objects);
  EstimatorOptions options = DefaultOptions();
  options.mode = AssociationMode::kStaticNearestNeighbour;
  Estimator estimator(options);
  const RunSummary summary = RunScenario(&world, &estimator, 12 * 8, 1);
  std::cout << testing::Describe(summary);
  EXPECT_GE(summary.movers_in_final_map, 1);
  EXPECT_EQ(summary.hypotheses, 0);
  for (const ObjectEstimate& e : summary.last.objects) {
    EXPECT_EQ(e.object_class, ObjectClass::kStatic);
  }
}

// Baseline (a) is plain EKF-SLAM: a landmark is in the map from its first sighting and never
// leaves it, whatever it does; nothing is classified, coasted or pruned.
TEST(ScenariosTest, StaticWorldBaselineIsPlainEkfSlam) {
  PointWorldOptions world_options;  // 180 degrees: the landmarks behind the robot are unseen
  std::vector<WorldObject> objects(4);
  objects[0] = {1, {6.0, 2.0}, {}, false};
  objects[1] = {2, {7.0, -2.5}, {}, false};
  objects[2] = {3, {9.0, 5.0}, {{1e18, {-0.2, -0.9}}}, true};
  objects[3] = {4, {4.0, -1.0}, {{1e18, {0.0, 0.0}}}, true};
  objects[3].visible_until_s = 3.0;  // an object that is taken away
  PointWorld world(world_options, SlowArc, objects);
  EstimatorOptions options = DefaultOptions();
  options.mode = AssociationMode::kStaticNearestNeighbour;
  Estimator estimator(options);
  std::mt19937_64 rng(1);
  int previous_objects = 0;
  for (int k = 0; k < 20 * 8; ++k) {
    const testing::WorldFrame frame = world.Next();
    for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
    const ScanResult result = estimator.ProcessScan(frame.scan, &rng);
    ASSERT_TRUE(result.processed);
    EXPECT_EQ(result.counts.pruned, 0);
    EXPECT_EQ(result.counts.level3_updates, 0);
    EXPECT_EQ(result.counts.manoeuvres, 0);
    EXPECT_EQ(result.counts.hypotheses, 0);
    EXPECT_EQ(result.counts.became_moving + result.counts.became_static +
                  result.counts.started_moving, 0);
    EXPECT_EQ(static_cast<int>(result.objects.size()), previous_objects + result.counts.new_objects);
    previous_objects = static_cast<int>(result.objects.size());
    for (const ObjectEstimate& e : result.objects) {
      EXPECT_EQ(e.object_class, ObjectClass::kStatic);
      EXPECT_TRUE(e.confirmed);
    }
  }
  // The walker left a trail of landmarks; the object taken away is still mapped.
  EXPECT_GT(previous_objects, 4);
  EXPECT_EQ(estimator.counters().hypotheses_generated, 0);
}

// Baseline (b), plain RANSAC over all pairs, reaches the same associations at a much higher
// number of hypotheses.
TEST(ScenariosTest, RansacOverAllPairsGeneratesFarMoreHypotheses) {
  auto run = [](AssociationMode mode) {
    PointWorldOptions world_options;
    std::vector<WorldObject> objects(4);
    objects[0] = {1, {9.0, 4.0}, {}, false};
    objects[1] = {2, {10.0, -4.0}, {}, false};
    objects[2] = {3, {6.0, -3.0}, {{1e18, {0.5, 0.8}}}, true};
    objects[3] = {4, {8.0, -3.4}, {{1e18, {0.0, 0.8}}}, true};
    PointWorld world(world_options, SlowArc, objects);
    EstimatorOptions options = DefaultOptions();
    options.mode = mode;
    Estimator estimator(options);
    return RunScenario(&world, &estimator, 9 * 8, 1);
  };
  const RunSummary ml = run(AssociationMode::kMlRansac);
  const RunSummary all = run(AssociationMode::kRansacAllPairs);
  std::cout << "hypotheses: ml_ransac " << ml.hypotheses << ", all pairs " << all.hypotheses << "\n";
  EXPECT_GT(all.hypotheses, 10 * ml.hypotheses);
  EXPECT_EQ(all.objects.at(3).id_switches, 0);
  EXPECT_EQ(all.objects.at(4).id_switches, 0);
}

// Same input, options and seed: the same estimate, bit for bit.
TEST(ScenariosTest, SameSeedSameResult) {
  auto run = [](uint64_t rng_seed) {
    PointWorldOptions world_options;
    std::vector<WorldObject> objects(4);
    objects[0] = {1, {9.0, 4.0}, {}, false};
    objects[1] = {2, {10.0, -4.0}, {}, false};
    objects[2] = {3, {6.0, -3.0}, {{1e18, {0.5, 0.8}}}, true};
    objects[3] = {4, {8.0, -3.4}, {{1e18, {0.0, 0.8}}}, true};
    PointWorld world(world_options, SlowArc, objects);
    Estimator estimator(DefaultOptions());
    RunScenario(&world, &estimator, 9 * 8, rng_seed);
    return estimator.state();
  };
  const SlamState a = run(11);
  const SlamState b = run(11);
  ASSERT_EQ(a.dim(), b.dim());
  EXPECT_EQ(a.mean(), b.mean());
  EXPECT_EQ(a.covariance(), b.covariance());
}

}  // namespace
}  // namespace slammtt
