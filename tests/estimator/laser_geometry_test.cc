// The laser geometry a log carries against the one the configuration gives (laser_geometry.h):
// parts taken, parts compared, the tolerance, unusable geometries, and a taken centred view that
// judges bearings exactly as the configured one.
#include "estimator/laser_geometry.h"

#include <gtest/gtest.h>

#include "estimator/estimator.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace slammtt {
namespace {

// s2-lobby's laser as its scenario gives it (config/scenarios/s2-lobby.yaml).
LaserGeometry LobbyLaser() {
  LaserGeometry g;
  g.mount.forward_m = 0.1;
  const double fov_rad = 180.0 * M_PI / 180.0;
  g.view.start_rad = -0.5 * fov_rad;
  g.view.end_rad = 0.5 * fov_rad;
  g.max_range_m = 30.0;
  return g;
}

// estimator/config/s2-lobby.yaml's geometry, as the configuration reader converts it.
EstimatorOptions LobbyConfigured() {
  EstimatorOptions o;
  o.sensor.forward_m = 0.1;
  o.field_of_view_rad = 180.0 * M_PI / 180.0;
  o.max_range_m = 30.0;
  return o;
}

TEST(LaserGeometryTest, TakesEveryPartTheConfigurationDoesNotGive) {
  const GeometryReconciliation r =
      ReconcileLaserGeometry(EstimatorOptions{}, ConfiguredGeometryParts{}, LobbyLaser());
  ASSERT_EQ(r.problem, "");
  EXPECT_EQ(r.disagreement, "");
  EXPECT_EQ(r.taken,
            "mount forward 0.1 m, left 0 m, yaw 0 deg; field of view -90 to 90 deg; "
            "max range 30 m");
  // Bit for bit the options estimator/config/s2-lobby.yaml gives: the same estimate.
  const EstimatorOptions configured = LobbyConfigured();
  EXPECT_EQ(r.options.sensor.forward_m, configured.sensor.forward_m);
  EXPECT_EQ(r.options.sensor.left_m, configured.sensor.left_m);
  EXPECT_EQ(r.options.sensor.yaw_rad, configured.sensor.yaw_rad);
  EXPECT_EQ(r.options.field_of_view_rad, configured.field_of_view_rad);
  EXPECT_EQ(r.options.field_of_view_start_rad, 0.0);
  EXPECT_EQ(r.options.field_of_view_end_rad, 0.0);
  EXPECT_EQ(r.options.max_range_m, configured.max_range_m);
  EXPECT_TRUE(FieldOfViewOf(r.options).symmetric);
}

TEST(LaserGeometryTest, KeepsAndComparesTheGivenPartsAndTakesTheOthers) {
  EstimatorOptions configured;
  configured.sensor.forward_m = 0.05;  // office's mount on the lobby's laser: disagrees
  configured.max_range_m = 30.0;       // agrees
  ConfiguredGeometryParts given;
  given.mount = true;
  given.max_range = true;
  const GeometryReconciliation r = ReconcileLaserGeometry(configured, given, LobbyLaser());
  ASSERT_EQ(r.problem, "");
  EXPECT_EQ(r.disagreement,
            "mount: configuration (forward 0.05 m, left 0 m, yaw 0 deg), log (forward 0.1 m, "
            "left 0 m, yaw 0 deg)");
  EXPECT_EQ(r.taken, "field of view -90 to 90 deg");
  EXPECT_EQ(r.options.sensor.forward_m, 0.05);  // the configuration's is used
  EXPECT_EQ(r.options.field_of_view_rad, M_PI);
}

TEST(LaserGeometryTest, DifferencesWithinTheToleranceAgree) {
  EstimatorOptions configured = LobbyConfigured();
  configured.sensor.forward_m += 0.9e-3;
  configured.max_range_m = 30.0009;
  configured.field_of_view_rad = (180.0 - 0.09) * M_PI / 180.0;  // each edge 0.045 deg off
  ConfiguredGeometryParts all{true, true, true};
  EXPECT_EQ(ReconcileLaserGeometry(configured, all, LobbyLaser()).disagreement, "");
  configured.max_range_m = 12.0;
  configured.field_of_view_rad = 2.0 * M_PI;
  EXPECT_EQ(ReconcileLaserGeometry(configured, all, LobbyLaser()).disagreement,
            "field of view: configuration -180 to 180 deg, log -90 to 90 deg; "
            "max range: configuration 12 m, log 30 m");
}

TEST(LaserGeometryTest, TwoFullCirclesAgreeWhereverTheyStart) {
  LaserGeometry log = LobbyLaser();
  log.view.start_rad = -0.5;
  log.view.end_rad = 2.0 * M_PI - 0.5;
  EstimatorOptions configured = LobbyConfigured();
  configured.field_of_view_rad = 2.0 * M_PI;
  EXPECT_EQ(ReconcileLaserGeometry(configured, {false, true, false}, log).disagreement, "");
}

TEST(LaserGeometryTest, AnAsymmetricViewIsTakenAsStartAndEnd) {
  LaserGeometry log = LobbyLaser();
  log.view.start_rad = -2.0;
  log.view.end_rad = 1.5;
  const GeometryReconciliation r = ReconcileLaserGeometry(EstimatorOptions{}, {}, log);
  ASSERT_EQ(r.problem, "");
  EXPECT_EQ(r.options.field_of_view_start_rad, -2.0);
  EXPECT_EQ(r.options.field_of_view_end_rad, 1.5);
  EXPECT_EQ(r.options.field_of_view_rad, 2.0 * M_PI);
  EXPECT_FALSE(FieldOfViewOf(r.options).symmetric);
}

TEST(LaserGeometryTest, AnUnstatedMaxRangeKeepsTheConfiguredOne) {
  LaserGeometry log = LobbyLaser();
  log.max_range_m = std::numeric_limits<double>::infinity();
  EstimatorOptions configured;
  configured.max_range_m = 12.0;
  const GeometryReconciliation r = ReconcileLaserGeometry(configured, {}, log);
  ASSERT_EQ(r.problem, "");
  EXPECT_EQ(r.options.max_range_m, 12.0);
  EXPECT_EQ(r.taken.find("max range"), std::string::npos) << r.taken;
}

TEST(LaserGeometryTest, AnUnusableGeometryIsNotUsed) {
  const EstimatorOptions configured = LobbyConfigured();
  LaserGeometry nan = LobbyLaser();
  nan.mount.left_m = std::nan("");
  LaserGeometry backwards = LobbyLaser();
  std::swap(backwards.view.start_rad, backwards.view.end_rad);
  LaserGeometry no_range = LobbyLaser();
  no_range.max_range_m = 0.0;
  LaserGeometry below_min = LobbyLaser();
  below_min.max_range_m = 0.005;  // below the estimator's min_range_m (0.01)
  for (const LaserGeometry& g : {nan, backwards, no_range, below_min}) {
    const GeometryReconciliation r = ReconcileLaserGeometry(configured, {}, g);
    EXPECT_NE(r.problem, "");
    EXPECT_EQ(r.taken, "");
    EXPECT_EQ(r.options.sensor.forward_m, configured.sensor.forward_m);
    EXPECT_EQ(r.options.max_range_m, configured.max_range_m);
  }
  EXPECT_EQ(LaserGeometryProblem(nan), "a value is not a finite number");
}

TEST(LaserGeometryTest, TheEstimatorTakesANewGeometryAndKeepsTheRest) {
  EstimatorOptions options;
  options.gate_d1_chi2 = 5.0;
  Estimator estimator(options);
  EstimatorOptions geometry = LobbyConfigured();
  geometry.gate_d1_chi2 = 7.0;  // not geometry: ignored
  estimator.SetLaserGeometry(geometry);
  EXPECT_EQ(estimator.options().sensor.forward_m, 0.1);
  EXPECT_EQ(estimator.options().field_of_view_rad, M_PI);
  EXPECT_EQ(estimator.options().gate_d1_chi2, 5.0);
  geometry.max_range_m = 0.001;  // below min_range_m
  EXPECT_THROW(estimator.SetLaserGeometry(geometry), std::invalid_argument);
  EXPECT_EQ(estimator.options().max_range_m, 30.0);
}

}  // namespace
}  // namespace slammtt
