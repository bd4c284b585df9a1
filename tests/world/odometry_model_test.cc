// The odometry model against paper eq. 1: exact in the noise-free cases, drifting with noise and
// slip, silent when the robot stands still.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tools/world/odometry_model.h"
#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

TEST(OdometryModelTest, WheelIncrementsOfAStraightLineAndATurnInPlace) {
  const WheelIncrements straight = WheelIncrementsForMotion(1.0, 0.0, 0.1, 0.4);
  EXPECT_DOUBLE_EQ(straight.left_rad, 10.0);
  EXPECT_DOUBLE_EQ(straight.right_rad, 10.0);
  // Turning by +pi/2 in place: each wheel travels D/2 * pi/2 = 0.1 pi m, left backwards.
  const WheelIncrements turn = WheelIncrementsForMotion(0.0, M_PI / 2, 0.1, 0.4);
  EXPECT_NEAR(turn.left_rad, -M_PI, 1e-12);
  EXPECT_NEAR(turn.right_rad, M_PI, 1e-12);
}

TEST(OdometryModelTest, NoiseFreeStraightLineEqualsEq1Exactly) {
  const Pose2D start{1.0, 2.0, 0.0};
  const Pose2D end = IntegrateWheelIncrements(
      start, WheelIncrementsForMotion(1.5, 0.0, 0.0975, 0.33), 0.0975, 0.33);
  EXPECT_DOUBLE_EQ(end.x_m, 2.5);
  EXPECT_DOUBLE_EQ(end.y_m, 2.0);
  EXPECT_DOUBLE_EQ(end.heading_rad, 0.0);
}

TEST(OdometryModelTest, NoiseFreeTurnInPlaceEqualsEq1Exactly) {
  const Pose2D start{1.0, 2.0, 0.25};
  const Pose2D end = IntegrateWheelIncrements(
      start, WheelIncrementsForMotion(0.0, 1.0, 0.0975, 0.33), 0.0975, 0.33);
  EXPECT_NEAR(end.x_m, 1.0, 1e-15);
  EXPECT_NEAR(end.y_m, 2.0, 1e-15);
  EXPECT_NEAR(end.heading_rad, 1.25, 1e-15);
}

TEST(OdometryModelTest, GeneralStepFollowsEq1WithTheNewHeading) {
  // w_L dt = 10, w_R dt = 12, r = 0.1, D = 0.4: Omega_r dt = 1.1, Omega_d dt = 0.5.
  const Pose2D end = IntegrateWheelIncrements(Pose2D{1.0, 2.0, 0.3}, WheelIncrements{10.0, 12.0},
                                              0.1, 0.4);
  EXPECT_NEAR(end.x_m, 1.0 + 1.1 * std::cos(0.8), 1e-12);
  EXPECT_NEAR(end.y_m, 2.0 + 1.1 * std::sin(0.8), 1e-12);
  EXPECT_NEAR(end.heading_rad, 0.8, 1e-12);
}

TEST(OdometryModelTest, HeadingIsWrapped) {
  const Pose2D end = IntegrateWheelIncrements(
      Pose2D{0.0, 0.0, 3.0}, WheelIncrementsForMotion(0.0, 0.5, 0.1, 0.4), 0.1, 0.4);
  EXPECT_NEAR(end.heading_rad, 3.5 - 2 * M_PI, 1e-12);
}

TEST(OdometryModelTest, NoiseFreeMeasurementDrawsNothingAndChangesNothing) {
  std::mt19937_64 rng(3);
  const std::mt19937_64 before = rng;
  const WheelIncrements truth{1.5, -0.5};
  const WheelIncrements measured = MeasureWheelIncrements(truth, OdometrySpec{}, rng);
  EXPECT_EQ(measured.left_rad, truth.left_rad);
  EXPECT_EQ(measured.right_rad, truth.right_rad);
  EXPECT_TRUE(rng == before);
}

TEST(OdometryModelTest, WheelsStandingStillReadNothingEvenWithNoise) {
  OdometrySpec spec;
  spec.encoder_noise_rad = 0.1;
  spec.slip_std = 0.1;
  OdometryIntegrator odometry(spec);
  std::mt19937_64 rng(1);
  odometry.Start(0);
  OdometryReading reading;
  for (int i = 1; i <= 100; ++i) reading = odometry.Update(i * 50000, 0.0, 0.0, rng);
  EXPECT_EQ(reading.pose.x_m, 0.0);
  EXPECT_EQ(reading.pose.y_m, 0.0);
  EXPECT_EQ(reading.pose.heading_rad, 0.0);
  EXPECT_EQ(reading.sequence, 100);
}

TEST(OdometryModelTest, ReadingsReportMeasuredVelocities) {
  OdometrySpec spec;
  spec.wheel_radius_m = 0.1;
  spec.axle_length_m = 0.4;
  OdometryIntegrator odometry(spec);
  std::mt19937_64 rng(1);
  const OdometryReading first = odometry.Start(1000);
  EXPECT_EQ(first.sequence, 0);
  EXPECT_EQ(first.linear_mps, 0.0);
  // 0.05 s: 0.05 m forward and 0.02 rad left.
  const OdometryReading r = odometry.Update(51000, 0.05, 0.02, rng);
  EXPECT_EQ(r.sequence, 1);
  EXPECT_NEAR(r.linear_mps, 1.0, 1e-12);
  EXPECT_NEAR(r.angular_radps, 0.4, 1e-12);
  EXPECT_NEAR(r.left_wheel_mps, 1.0 - 0.2 * 0.4, 1e-12);
  EXPECT_NEAR(r.right_wheel_mps, 1.0 + 0.2 * 0.4, 1e-12);
}

TEST(OdometryModelTest, SlipBiasOfOneWheelTurnsTheOdometryByTheExpectedAngle) {
  OdometrySpec spec;
  spec.right_slip_bias = 0.01;  // the right encoder reads 1 % more than the ground
  OdometryIntegrator odometry(spec);
  std::mt19937_64 rng(1);
  odometry.Start(0);
  OdometryReading reading;
  for (int i = 1; i <= 200; ++i) reading = odometry.Update(i * 50000, 0.05, 0.0, rng);
  // 10 m straight: extra right rotation 0.01 * 10 m / D.
  EXPECT_NEAR(reading.pose.heading_rad, 0.01 * 10.0 / spec.axle_length_m, 1e-9);
  EXPECT_GT(reading.pose.y_m, 0.5);  // it believes it curved left
}

// Position error of the odometry against the truth of a robot driving a fixed path.
double OdometryPositionError(const OdometrySpec& spec, uint64_t seed, double duration_s) {
  Scenario scenario;
  scenario.duration_s = duration_s;
  scenario.odometry = spec;
  scenario.robot.profile = {VelocitySegment{10.0, 1.0, 0.0}, VelocitySegment{10.0, 0.8, 0.15}};
  scenario.robot.loop = true;
  WorldSimulator world(scenario, seed, SensorOutput::kScans);
  OdometryReading last;
  while (!world.Done()) {
    const WorldEvent event = world.Next();
    if (event.kind == WorldEvent::Kind::kOdometry) last = event.odometry;
  }
  // The robot starts at the origin of the world with heading 0, so odometry and world frames
  // coincide.
  return std::hypot(last.pose.x_m - world.robot().pose.x_m, last.pose.y_m - world.robot().pose.y_m);
}

TEST(OdometryModelTest, NoiseFreeErrorOnArcsIsOnlyTheDiscretisationOfEq1) {
  // Eq. 1 moves each step along the heading at its end, not along the chord (half a step's
  // rotation off): on arcs the noise-free odometry drifts a little, less with shorter steps.
  OdometrySpec at_20_hz;
  OdometrySpec at_40_hz;
  at_40_hz.rate_hz = 40.0;
  const double error_20 = OdometryPositionError(at_20_hz, 1, 100.0);
  const double error_40 = OdometryPositionError(at_40_hz, 1, 100.0);
  EXPECT_GT(error_20, 0.0);
  EXPECT_LT(error_20, 0.05);  // over 90 m of path
  EXPECT_LT(error_40, 0.6 * error_20);
}

TEST(OdometryModelTest, ErrorGrowsWithTimeAndWithNoise) {
  OdometrySpec noisy;
  noisy.encoder_noise_rad = 0.01;
  noisy.slip_std = 0.02;
  OdometrySpec noisier = noisy;
  noisier.encoder_noise_rad = 0.04;
  noisier.slip_std = 0.08;
  double short_run = 0.0;
  double long_run = 0.0;
  double long_noisier = 0.0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    short_run += OdometryPositionError(noisy, seed, 10.0);
    long_run += OdometryPositionError(noisy, seed, 100.0);
    long_noisier += OdometryPositionError(noisier, seed, 100.0);
  }
  EXPECT_GT(short_run, 0.0);
  EXPECT_GT(long_run, 2.0 * short_run);
  EXPECT_GT(long_noisier, 2.0 * long_run);
}

}  // namespace
}  // namespace slammtt
