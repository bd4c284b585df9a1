// Sensor artefacts (laser_model.h): off by default (the same draws as before), mixed pixels at
// depth edges, dropouts on surfaces and at grazing incidence, range-dependent noise, and the
// RPLIDAR's uneven, drifting beam angles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tools/world/laser_model.h"
#include "tools/world/portable_random.h"

namespace slammtt {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(LaserArtefactsTest, OffByDefaultDrawsExactlyAsBefore) {
  LaserSpec laser;
  const std::vector<double> angles = LaserBeamAngles(laser);
  const std::vector<BeamHit> hits =
      CastBeams(Pose2D{}, angles, {Circle{3.0, 0.0, 0.5}}, {Segment{-5, -5, -5, 5}}, 12.0);
  std::mt19937_64 a(3);
  std::mt19937_64 b(3);
  std::mt19937_64 artefacts(4);
  const std::vector<SimulatedBeam> plain = MeasureScan(laser, angles, hits, a);
  const std::vector<SimulatedBeam> with =
      MeasureScan(laser, angles, hits, ArtefactInputs{}, b, artefacts);
  ASSERT_EQ(plain.size(), with.size());
  for (size_t i = 0; i < plain.size(); ++i) ASSERT_EQ(plain[i].range_m, with[i].range_m);
  EXPECT_EQ(a(), b());
  std::mt19937_64 fresh(4);
  EXPECT_EQ(artefacts(), fresh());  // no artefact draw at all
  BeamAngleSequence even(laser);
  EXPECT_FALSE(even.sampled());
  EXPECT_EQ(even.Next(a), angles);
}

TEST(LaserArtefactsTest, MixedPixelsLieBetweenTheTwoSurfacesOfAnEdge) {
  LaserSpec laser;
  laser.range_noise_m = 0.0;
  laser.resolution_deg = 0.1;
  laser.artefacts.mixed_pixel_probability = 1.0;
  laser.artefacts.beam_divergence_deg = 0.5;
  const std::vector<double> angles = LaserBeamAngles(laser);
  // A post at 2 m in front of a wall at 5 m.
  const std::vector<Circle> post = {Circle{2.0, 0.0, 0.2}};
  const std::vector<Segment> wall = {Segment{5.0, -5.0, 5.0, 5.0}};
  const Pose2D sensor;
  const double half = 0.25 * kDeg;
  std::vector<double> low(angles), high(angles);
  for (double& a : low) a -= half;
  for (double& a : high) a += half;
  ArtefactInputs inputs;
  inputs.lower_edge_hits = CastBeams(sensor, low, post, wall, 12.0);
  inputs.upper_edge_hits = CastBeams(sensor, high, post, wall, 12.0);
  std::mt19937_64 rng(1);
  std::mt19937_64 artefact_rng(2);
  const std::vector<SimulatedBeam> beams =
      MeasureScan(laser, angles, CastBeams(sensor, angles, post, wall, 12.0), inputs, rng,
                  artefact_rng);
  int mixed = 0;
  for (const SimulatedBeam& beam : beams) {
    if (!beam.mixed_pixel) continue;
    ++mixed;
    EXPECT_GT(beam.range_m, 1.8);
    EXPECT_LT(beam.range_m, 5.1);
    // Only beams within half the divergence of the post's silhouette edges (asin(0.2 / 2)).
    const double edge = std::asin(0.1);
    EXPECT_NEAR(std::abs(beam.angle_rad), edge, half + 1e-9);
  }
  // 0.5 degree footprint, 0.1 degree spacing: about 5 beams at each of the two edges.
  EXPECT_GE(mixed, 8);
  EXPECT_LE(mixed, 12);
}

TEST(LaserArtefactsTest, DropoutsOnDarkSurfacesAndAtGrazingIncidence) {
  LaserSpec laser;
  laser.artefacts.grazing_dropout_deg = 75.0;
  const std::vector<double> angles = LaserBeamAngles(laser);
  // A wall along y = 1 from x = -20 to 20: beams at more than 75 degrees from its normal
  // (|angle - 90 deg| > 75) graze it.
  const std::vector<Segment> wall = {Segment{-20.0, 1.0, 20.0, 1.0}};
  const std::vector<BeamHit> hits = CastBeams(Pose2D{}, angles, {}, wall, 30.0);
  std::mt19937_64 rng(1);
  std::mt19937_64 artefact_rng(2);
  laser.max_range_m = 30.0;
  const std::vector<SimulatedBeam> beams =
      MeasureScan(laser, angles, hits, ArtefactInputs{}, rng, artefact_rng);
  for (const SimulatedBeam& beam : beams) {
    if (beam.segment < 0) continue;
    const double incidence_deg = std::abs(beam.angle_rad / kDeg - 90.0);
    if (incidence_deg > 75.0 + 1e-6) {
      EXPECT_TRUE(beam.dropout) << beam.angle_rad / kDeg;
      EXPECT_FALSE(beam.valid);
    } else if (incidence_deg < 75.0 - 1e-6) {
      EXPECT_TRUE(beam.valid) << beam.angle_rad / kDeg;
    }
  }
  // A black surface: 30 % of its beams give nothing.
  LaserSpec plain;
  plain.max_range_m = 30.0;
  ArtefactInputs dark;
  dark.segment_dropout_probability = {0.3};
  int hit = 0;
  int dropped = 0;
  for (int scan = 0; scan < 50; ++scan) {
    for (const SimulatedBeam& beam : MeasureScan(plain, angles, hits, dark, rng, artefact_rng)) {
      if (beam.segment < 0 || beam.true_range_m > 30.0) continue;
      ++hit;
      dropped += beam.dropout ? 1 : 0;
      EXPECT_EQ(beam.dropout, !beam.valid);
    }
  }
  EXPECT_NEAR(static_cast<double>(dropped) / hit, 0.3, 0.02);
}

TEST(LaserArtefactsTest, RangeNoiseGrowsWithRange) {
  LaserSpec laser;
  laser.range_noise_m = 0.01;
  laser.artefacts.range_noise_per_m = 0.005;
  laser.max_range_m = 30.0;
  const std::vector<double> angles = {0.0, M_PI};
  // 2 m ahead, 10 m behind: sigma 0.02 and 0.06 m.
  const std::vector<Segment> walls = {Segment{2.0, -1.0, 2.0, 1.0},
                                      Segment{-10.0, -1.0, -10.0, 1.0}};
  const std::vector<BeamHit> hits = CastBeams(Pose2D{}, angles, {}, walls, 30.0);
  std::mt19937_64 rng(5);
  std::mt19937_64 artefact_rng(6);
  double sum2[2] = {0.0, 0.0};
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const std::vector<SimulatedBeam> beams =
        MeasureScan(laser, angles, hits, ArtefactInputs{}, rng, artefact_rng);
    for (size_t k = 0; k < 2; ++k) {
      const double e = beams[k].range_m - beams[k].true_range_m;
      sum2[k] += e * e;
    }
  }
  EXPECT_NEAR(std::sqrt(sum2[0] / n), 0.02, 0.001);
  EXPECT_NEAR(std::sqrt(sum2[1] / n), 0.06, 0.002);
}

TEST(LaserArtefactsTest, RplidarAnglesAreUnevenClockwiseAndStartAnywhere) {
  LaserSpec laser;  // 10 Hz
  laser.artefacts.sample_rate_hz = 4000.0;  // express mode: 400 samples per revolution
  laser.artefacts.rotation_jitter = 0.01;
  laser.artefacts.angle_jitter_deg = 0.05;
  BeamAngleSequence sequence(laser);
  ASSERT_TRUE(sequence.sampled());
  std::mt19937_64 rng(9);
  int min_beams = 1 << 30;
  int max_beams = 0;
  double min_first = 1e9;
  double max_first = -1e9;
  int not_decreasing = 0;
  for (int scan = 0; scan < 200; ++scan) {
    const std::vector<double> angles = sequence.Next(rng);
    min_beams = std::min(min_beams, static_cast<int>(angles.size()));
    max_beams = std::max(max_beams, static_cast<int>(angles.size()));
    // Device angle of the first sample: -angle, in [0, step) plus jitter.
    const double first_deg = -angles.front() / kDeg;
    min_first = std::min(min_first, first_deg);
    max_first = std::max(max_first, first_deg);
    for (size_t i = 1; i < angles.size(); ++i) {
      double step = WrapAngle(angles[i - 1] - angles[i]) / kDeg;  // clockwise: positive
      EXPECT_LT(std::abs(step - 0.9), 0.5);
      if (step <= 0.0) ++not_decreasing;
    }
  }
  EXPECT_LT(min_beams, 400);
  EXPECT_GT(max_beams, 400);
  EXPECT_GE(min_beams, 380);  // 400 / (1 -+ 5 sigma of the 1 % speed jitter)
  EXPECT_LE(max_beams, 420);
  EXPECT_LT(min_first, 0.2);
  EXPECT_GT(max_first, 0.6);
  EXPECT_LT(not_decreasing, 100);  // jitter 0.05 degree rarely swaps neighbours 0.9 apart
}

}  // namespace
}  // namespace slammtt
