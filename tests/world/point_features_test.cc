// Point features of the paper's simulation: exact without noise, the visibility rule (field of
// view, range, occlusion, line of sight), detection probability and the noise statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tools/world/laser_model.h"
#include "tools/world/point_features.h"

namespace slammtt {
namespace {

constexpr double kDeg = M_PI / 180.0;

LaserSpec HalfCircleLaser() {
  LaserSpec laser;
  laser.fov_deg = 180.0;
  laser.resolution_deg = 1.0;
  laser.min_range_m = 0.1;
  laser.max_range_m = 30.0;
  laser.range_noise_m = 0.0;
  return laser;
}

FeatureSpec NoiseFree() {
  FeatureSpec spec;
  spec.range_noise_m = 0.0;
  spec.bearing_noise_deg = 0.0;
  return spec;
}

std::vector<PointFeature> Emit(const Pose2D& sensor, const std::vector<Circle>& circles,
                               const LaserSpec& laser, const FeatureSpec& spec,
                               std::vector<bool>* visible, uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  const std::vector<double> angles = LaserBeamAngles(laser);
  const std::vector<SimulatedBeam> beams =
      MeasureScan(laser, angles, CastBeams(sensor, angles, circles, laser.max_range_m), rng);
  const std::vector<int> counts = CountBeamsPerObject(beams, static_cast<int>(circles.size()));
  return EmitPointFeatures(sensor, circles, counts, laser, spec, rng, visible);
}

TEST(PointFeaturesTest, NoiseFreeFeatureIsTheCentreInTheSensorFrame) {
  // Sensor at (1, 1) facing +y; object at (1 - 3, 1 + 4): range 5, bearing atan2(3, 4)... in the
  // sensor frame x forward (+y world), y left (-x world): (4, 3).
  std::vector<bool> visible;
  const std::vector<PointFeature> f =
      Emit(Pose2D{1.0, 1.0, M_PI / 2}, {Circle{-2.0, 5.0, 0.3}}, HalfCircleLaser(), NoiseFree(),
           &visible);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(f[0].range_m, 5.0, 1e-12);
  EXPECT_NEAR(f[0].bearing_rad, std::atan2(3.0, 4.0), 1e-12);
  EXPECT_DOUBLE_EQ(f[0].width_m, 0.6);
  EXPECT_EQ(f[0].object, 0);
  EXPECT_TRUE(visible[0]);
}

TEST(PointFeaturesTest, OutsideTheFieldOfViewOrRangeIsInvisible) {
  std::vector<bool> visible;
  const std::vector<Circle> circles = {
      Circle{-5.0, 0.0, 0.3},   // behind a 180-degree sensor
      Circle{40.0, 0.0, 0.3},   // beyond 30 m
      Circle{5.0, 5.0, 0.3},    // in view
      Circle{0.05, 0.0, 0.01},  // nearer than min range
  };
  const std::vector<PointFeature> f =
      Emit(Pose2D{}, circles, HalfCircleLaser(), NoiseFree(), &visible);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].object, 2);
  EXPECT_EQ(visible, (std::vector<bool>{false, false, true, false}));
  // A 360-degree sensor sees the one behind it.
  LaserSpec full = HalfCircleLaser();
  full.fov_deg = 360.0;
  Emit(Pose2D{}, circles, full, NoiseFree(), &visible);
  EXPECT_TRUE(visible[0]);
}

TEST(PointFeaturesTest, FullyOccludedObjectIsInvisiblePartlyOccludedIsVisible) {
  std::vector<bool> visible;
  // A small mover right behind a big landmark: every beam towards it hits the landmark.
  Emit(Pose2D{}, {Circle{5.0, 0.0, 1.0}, Circle{8.0, 0.0, 0.25}}, HalfCircleLaser(), NoiseFree(),
       &visible);
  EXPECT_TRUE(visible[0]);
  EXPECT_FALSE(visible[1]);
  // Moved sideways so that some beams pass the landmark: visible again.
  Emit(Pose2D{}, {Circle{5.0, 0.0, 1.0}, Circle{8.0, 1.7, 0.25}}, HalfCircleLaser(), NoiseFree(),
       &visible);
  EXPECT_TRUE(visible[1]);
}

TEST(PointFeaturesTest, SmallObjectBetweenBeamsIsVisibleByLineOfSight) {
  LaserSpec coarse = HalfCircleLaser();
  coarse.resolution_deg = 10.0;  // beams at -90, -80, ..., 90 degrees
  std::vector<bool> visible;
  // At bearing 5 degrees, 10 m away, radius 0.1 m: no beam hits it.
  const Circle small{10.0 * std::cos(5 * kDeg), 10.0 * std::sin(5 * kDeg), 0.1};
  std::mt19937_64 rng(1);
  const std::vector<double> angles = LaserBeamAngles(coarse);
  const auto beams = MeasureScan(coarse, angles, CastBeams(Pose2D{}, angles, {small}, 30.0), rng);
  EXPECT_EQ(CountBeamsPerObject(beams, 1)[0], 0);
  Emit(Pose2D{}, {small}, coarse, NoiseFree(), &visible);
  EXPECT_TRUE(visible[0]);
  // The same object with something on the line of sight (and still no beam on it): hidden.
  const Circle blocker{5.0 * std::cos(5 * kDeg), 5.0 * std::sin(5 * kDeg), 0.1};
  Emit(Pose2D{}, {small, blocker}, coarse, NoiseFree(), &visible);
  EXPECT_FALSE(visible[0]);
}

TEST(PointFeaturesTest, FeaturesAreSortedByBearing) {
  std::vector<bool> visible;
  const std::vector<PointFeature> f =
      Emit(Pose2D{}, {Circle{5.0, 3.0, 0.2}, Circle{5.0, -3.0, 0.2}, Circle{5.0, 0.0, 0.2}},
           HalfCircleLaser(), NoiseFree(), &visible);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].object, 1);
  EXPECT_EQ(f[1].object, 2);
  EXPECT_EQ(f[2].object, 0);
}

TEST(PointFeaturesTest, DetectionProbabilityZeroEmitsNothing) {
  FeatureSpec never = NoiseFree();
  never.detection_probability = 0.0;
  std::vector<bool> visible;
  EXPECT_TRUE(Emit(Pose2D{}, {Circle{5.0, 0.0, 0.2}}, HalfCircleLaser(), never, &visible).empty());
  EXPECT_FALSE(visible[0]);
}

TEST(PointFeaturesTest, NoiseHasThePapersStandardDeviationsAndCovariance) {
  const FeatureSpec paper;  // 0.2 m, 2 degrees
  LaserSpec laser = HalfCircleLaser();
  laser.resolution_deg = 0.5;
  std::mt19937_64 rng(11);
  const std::vector<Circle> circles = {Circle{8.0, 6.0, 0.25}};  // range 10, bearing 36.87 deg
  const std::vector<int> counts = {3};
  double sum_r = 0, sum_r2 = 0, sum_b = 0, sum_b2 = 0;
  const int n = 20000;
  std::vector<bool> visible;
  for (int i = 0; i < n; ++i) {
    const std::vector<PointFeature> f =
        EmitPointFeatures(Pose2D{}, circles, counts, laser, paper, rng, &visible);
    ASSERT_EQ(f.size(), 1u);
    const double dr = f[0].range_m - 10.0;
    const double db = f[0].bearing_rad - std::atan2(6.0, 8.0);
    sum_r += dr;
    sum_r2 += dr * dr;
    sum_b += db;
    sum_b2 += db * db;
    if (i == 0) {
      EXPECT_DOUBLE_EQ(f[0].range_var_m2, 0.04);
      EXPECT_NEAR(f[0].bearing_var_rad2, std::pow(2 * kDeg, 2), 1e-15);
    }
  }
  // Standard errors: mean 0.2/sqrt(n) = 0.0014 m; std of the std about 0.2/sqrt(2n) = 0.001 m.
  EXPECT_NEAR(sum_r / n, 0.0, 0.006);
  EXPECT_NEAR(std::sqrt(sum_r2 / n), 0.2, 0.005);
  EXPECT_NEAR(sum_b / n, 0.0, 0.0006);
  EXPECT_NEAR(std::sqrt(sum_b2 / n), 2 * kDeg, 0.0009);
}

TEST(LaserModelTest, ValidityMinimumRangeAndNoise) {
  LaserSpec laser = HalfCircleLaser();
  laser.min_range_m = 0.5;
  laser.range_noise_m = 0.01;
  const std::vector<double> angles = {0.0, 0.5, -0.5, 1.5};
  const std::vector<BeamHit> hits = {BeamHit{4.0, 0}, BeamHit{0.2, 1}, BeamHit{}, BeamHit{30.0, 2}};
  std::mt19937_64 rng(3);
  const std::vector<SimulatedBeam> beams = MeasureScan(laser, angles, hits, rng);
  ASSERT_EQ(beams.size(), 4u);
  EXPECT_TRUE(beams[0].valid);
  EXPECT_NEAR(beams[0].range_m, 4.0, 0.06);
  EXPECT_NE(beams[0].range_m, 4.0);
  EXPECT_EQ(beams[0].object, 0);
  EXPECT_FALSE(beams[1].valid);  // nearer than min range: invalid but names what it hit
  EXPECT_EQ(beams[1].object, 1);
  EXPECT_EQ(beams[1].range_m, 0.0);
  EXPECT_FALSE(beams[2].valid);
  EXPECT_EQ(beams[2].object, -1);
  EXPECT_TRUE(beams[3].valid);
  EXPECT_LE(beams[3].range_m, 30.0);  // clamped into [min, max]
  EXPECT_EQ(CountBeamsPerObject(beams, 3), (std::vector<int>{1, 0, 1}));
  for (size_t i = 0; i < beams.size(); ++i) EXPECT_EQ(beams[i].angle_rad, angles[i]);
}

TEST(LaserModelTest, RangeNoiseHasTheConfiguredStandardDeviation) {
  LaserSpec laser = HalfCircleLaser();
  laser.range_noise_m = 0.03;
  std::mt19937_64 rng(5);
  const int n = 20000;
  const std::vector<double> angles(static_cast<size_t>(n), 0.0);
  const std::vector<BeamHit> hits(static_cast<size_t>(n), BeamHit{7.0, 0});
  double sum = 0, sum2 = 0;
  for (const SimulatedBeam& b : MeasureScan(laser, angles, hits, rng)) {
    sum += b.range_m - 7.0;
    sum2 += (b.range_m - 7.0) * (b.range_m - 7.0);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.03, 0.0008);
}

}  // namespace
}  // namespace slammtt
