// Long randomised runs: random robot motion, random static and moving objects (starting,
// stopping, turning, appearing, vanishing), missed detections, and every kind of bad input
// mixed in (NaN and out-of-range features, odometry outages, time gaps, repeated and older
// scans, bursts of features beyond the object cap). The state must never hold a NaN and the
// covariance must stay symmetric and positive semi-definite.
// Default: 6 seeds x 60 s of simulated time; SLAMMTT_LONG_TESTS=1: 40 seeds x 300 s.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdlib>
#include <limits>
#include <random>

#include "estimator/estimator.h"
#include "estimator/testing/point_world.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::VelocitySegment;
using testing::WorldFrame;
using testing::WorldObject;

bool LongRun() {
  const char* value = std::getenv("SLAMMTT_LONG_TESTS");
  return value != nullptr && std::string(value) == "1";
}

std::vector<WorldObject> RandomObjects(std::mt19937_64* rng, double duration_s) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<WorldObject> objects;
  const int statics = 5 + static_cast<int>(25 * unit(*rng));
  const int movers = 2 + static_cast<int>(12 * unit(*rng));
  int64_t id = 1;
  for (int k = 0; k < statics + movers; ++k) {
    WorldObject o;
    o.id = id++;
    o.start_m = Eigen::Vector2d(-20.0 + 60.0 * unit(*rng), -20.0 + 40.0 * unit(*rng));
    o.mover = k >= statics;
    if (o.mover) {
      double t = 0.0;
      while (t < duration_s) {
        t += 1.0 + 8.0 * unit(*rng);
        const double speed = unit(*rng) < 0.25 ? 0.0 : 0.3 + 1.5 * unit(*rng);
        const double heading = 2.0 * M_PI * unit(*rng);
        o.segments.push_back({t, speed * Eigen::Vector2d(std::cos(heading), std::sin(heading))});
      }
    }
    if (unit(*rng) < 0.3) {
      o.visible_from_s = duration_s * unit(*rng);
      o.visible_until_s = o.visible_from_s + duration_s * unit(*rng);
    }
    objects.push_back(o);
  }
  return objects;
}

void CheckHealthy(const Estimator& estimator, bool eigen, const std::string& where) {
  const SlamState& state = estimator.state();
  ASSERT_TRUE(state.mean().allFinite()) << where;
  const auto p = state.covariance();
  ASSERT_TRUE(p.allFinite()) << where;
  ASSERT_TRUE(p == p.transpose()) << where;
  for (int i = 0; i < state.dim(); ++i) ASSERT_GE(p(i, i), 0.0) << where << " diagonal " << i;
  if (eigen && state.dim() > 0) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(p, Eigen::EigenvaluesOnly);
    ASSERT_GE(solver.eigenvalues().minCoeff(), -1e-9 * std::max(1.0, p.trace())) << where;
  }
}

void Soak(uint64_t seed, double duration_s) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PointWorldOptions world_options;
  world_options.seed = seed;
  world_options.field_of_view_rad = unit(rng) < 0.5 ? M_PI : 2.0 * M_PI;
  world_options.detection_probability = 0.75 + 0.25 * unit(rng);
  world_options.scan_period_s = unit(rng) < 0.5 ? 0.125 : 0.1;
  world_options.sensor.forward_m = 0.1;
  const std::vector<WorldObject> objects = RandomObjects(&rng, duration_s);
  std::vector<Eigen::Vector2d> commands;
  for (int k = 0; k < static_cast<int>(duration_s / 5.0) + 2; ++k) {
    commands.emplace_back(2.0 * unit(rng), -0.6 + 1.2 * unit(rng));
  }
  PointWorld world(world_options,
                   [commands](double t) { return commands[static_cast<size_t>(t / 5.0)]; },
                   objects);
  EstimatorOptions options;
  options.mode = static_cast<AssociationMode>(seed % 3);
  options.sensor = world_options.sensor;
  options.field_of_view_rad = world_options.field_of_view_rad;
  options.max_objects = 60;
  Estimator estimator(options);
  std::mt19937_64 ransac_rng(seed);
  const int scans = static_cast<int>(duration_s / world_options.scan_period_s);
  bool odometry_outage = false;
  for (int k = 0; k < scans; ++k) {
    WorldFrame frame = world.Next();
    if (unit(rng) < 0.02) odometry_outage = !odometry_outage;
    if (!odometry_outage) {
      for (const OdometryReading& reading : frame.odometry) {
        OdometryReading r = reading;
        if (unit(rng) < 0.005) r.pose(0) = std::numeric_limits<double>::quiet_NaN();
        estimator.AddOdometry(r);
        if (unit(rng) < 0.005) estimator.AddOdometry(r);  // duplicate
      }
    }
    if (unit(rng) < 0.01) continue;  // a lost scan: a time gap for the next one
    if (unit(rng) < 0.005) {
      // A long silence (beyond max_time_gap_s).
      for (int skip = 0; skip < 12 && k + 1 < scans; ++skip, ++k) world.Next();
      continue;
    }
    for (FeatureReading& f : frame.scan.features) {
      const double u = unit(rng);
      if (u < 0.01) f.range_m = std::numeric_limits<double>::quiet_NaN();
      else if (u < 0.02) f.bearing_rad = std::numeric_limits<double>::infinity();
      else if (u < 0.03) f.range_m = 1e9;
      else if (u < 0.035) f.range_var_m2 = -1.0;
    }
    if (unit(rng) < 0.01) {
      for (int burst = 0; burst < 80; ++burst) {
        FeatureReading f;
        f.range_m = 1.0 + 25.0 * unit(rng);
        f.bearing_rad = -1.5 + 3.0 * unit(rng);
        frame.scan.features.push_back(f);
      }
    }
    if (unit(rng) < 0.03) frame.scan.features.clear();
    estimator.ProcessScan(frame.scan, &ransac_rng);
    if (unit(rng) < 0.01) estimator.ProcessScan(frame.scan, &ransac_rng);  // repeated scan
    const std::string where = "seed " + std::to_string(seed) + " scan " + std::to_string(k);
    CheckHealthy(estimator, k % 40 == 39, where);
    if (::testing::Test::HasFatalFailure()) return;
  }
  CheckHealthy(estimator, true, "seed " + std::to_string(seed) + " end");
  const EstimatorCounters& c = estimator.counters();
  EXPECT_GT(c.features_rejected, 0);
  EXPECT_GT(c.scans_processed, scans / 2);
  EXPECT_LE(estimator.state().num_objects(), options.max_objects);
}

TEST(EstimatorSoakTest, StateStaysFiniteSymmetricPositiveSemiDefinite) {
  const bool long_run = LongRun();
  const int seeds = long_run ? 40 : 6;
  const double duration_s = long_run ? 300.0 : 60.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    Soak(static_cast<uint64_t>(seed), duration_s);
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace slammtt
