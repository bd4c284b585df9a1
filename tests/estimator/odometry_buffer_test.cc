// The odometry between two scans (estimator/odometry_buffer.h) and the prediction step that
// uses it (estimator/scan_prediction.h).
#include "estimator/odometry_buffer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "estimator/scan_prediction.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::kSecond;

OdometryReading Reading(int64_t utime, double x, double y, double heading, double linear = 0.0,
                        double angular = 0.0) {
  OdometryReading r;
  r.utime = utime;
  r.pose = Eigen::Vector3d(x, y, heading);
  r.linear_mps = linear;
  r.angular_radps = angular;
  return r;
}

const ExtrapolationNoise kExtrapolation{0.09, 0.09, 30.0};

TEST(OdometryBufferTest, ReadingsUpToTheScanAreOneIncrementEach) {
  OdometryBuffer buffer;
  EXPECT_FALSE(buffer.anchored());
  buffer.Add(Reading(0, 5.0, 5.0, 1.0));  // anchors: motion counts from here
  EXPECT_TRUE(buffer.anchored());
  buffer.Add(Reading(kSecond / 10, 5.1, 5.0, 1.0));
  buffer.Add(Reading(kSecond / 5, 5.1, 5.0, 1.2));
  RobotMotionAccumulator motion(Eigen::Vector3d::Zero());
  EXPECT_TRUE(buffer.AddMotionTo(kSecond / 5, OdometryNoiseOptions(), kExtrapolation, &motion));
  // The same two increments by hand.
  const OdometryIncrement a =
      IncrementBetweenOdometryPoses({5.0, 5.0, 1.0}, {5.1, 5.0, 1.0});
  const OdometryIncrement b =
      IncrementBetweenOdometryPoses({5.1, 5.0, 1.0}, {5.1, 5.0, 1.2});
  const Eigen::Vector3d expected =
      PredictRobotPose(PredictRobotPose(Eigen::Vector3d::Zero(), a), b);
  EXPECT_NEAR((motion.pose() - expected).norm(), 0.0, 1e-12);
  EXPECT_GT(motion.noise()(0, 0), 0.0);
}

TEST(OdometryBufferTest, AScanBetweenTwoReadingsTakesTheInterpolatedPart) {
  OdometryBuffer buffer;
  buffer.Add(Reading(0, 0.0, 0.0, 0.0, 1.0));
  buffer.Add(Reading(kSecond, 1.0, 0.0, 0.0, 1.0));
  RobotMotionAccumulator motion(Eigen::Vector3d::Zero());
  EXPECT_TRUE(
      buffer.AddMotionTo(kSecond / 4, OdometryNoiseOptions(), kExtrapolation, &motion));
  EXPECT_NEAR(motion.pose()(0), 0.25, 1e-12);
  // The rest of the increment goes to the next scan.
  RobotMotionAccumulator rest(Eigen::Vector3d::Zero());
  EXPECT_TRUE(buffer.AddMotionTo(kSecond, OdometryNoiseOptions(), kExtrapolation, &rest));
  EXPECT_NEAR(rest.pose()(0), 0.75, 1e-12);
}

TEST(OdometryBufferTest, PastTheLastReadingTheMotionIsExtrapolatedWithMoreNoise) {
  OdometryBuffer buffer;
  buffer.Add(Reading(0, 0.0, 0.0, 0.0, 0.5, 0.1));
  RobotMotionAccumulator motion(Eigen::Vector3d::Zero());
  EXPECT_FALSE(buffer.AddMotionTo(2 * kSecond, OdometryNoiseOptions(), kExtrapolation, &motion))
      << "no reading covers the interval";
  EXPECT_NEAR(motion.pose()(0), std::cos(0.2) * 1.0, 1e-12);
  EXPECT_NEAR(motion.pose()(2), 0.2, 1e-12);
  // 0.3 m/s of extrapolation noise (variance rate 0.09) over 2 s, besides the odometry model.
  RobotMotionAccumulator without(Eigen::Vector3d::Zero());
  OdometryBuffer same;
  same.Add(Reading(0, 0.0, 0.0, 0.0, 0.5, 0.1));
  same.AddMotionTo(2 * kSecond, OdometryNoiseOptions(), ExtrapolationNoise{0.0, 0.0, 30.0},
                   &without);
  EXPECT_GT(motion.noise()(0, 0), without.noise()(0, 0) + 0.3);
  // At most max_s of extrapolation.
  OdometryBuffer capped;
  capped.Add(Reading(0, 0.0, 0.0, 0.0, 0.5, 0.0));
  RobotMotionAccumulator far(Eigen::Vector3d::Zero());
  capped.AddMotionTo(100 * kSecond, OdometryNoiseOptions(), ExtrapolationNoise{0.0, 0.0, 10.0},
                     &far);
  EXPECT_NEAR(far.pose()(0), 5.0, 1e-12);
}

TEST(OdometryBufferTest, ALateReadingRefreshesTheVelocitiesAndClearForgetsEverything) {
  OdometryBuffer buffer;
  buffer.Add(Reading(0, 0.0, 0.0, 0.0, 0.0));
  RobotMotionAccumulator first(Eigen::Vector3d::Zero());
  buffer.AddMotionTo(kSecond, OdometryNoiseOptions(), kExtrapolation, &first);  // cursor at 1 s
  buffer.Add(Reading(kSecond / 2, 0.0, 0.0, 0.0, 2.0));  // older than the cursor: velocity only
  RobotMotionAccumulator second(Eigen::Vector3d::Zero());
  buffer.AddMotionTo(2 * kSecond, OdometryNoiseOptions(), kExtrapolation, &second);
  EXPECT_NEAR(second.pose()(0), 2.0, 1e-12);
  buffer.Clear();
  EXPECT_FALSE(buffer.anchored());
  RobotMotionAccumulator none(Eigen::Vector3d::Zero());
  EXPECT_FALSE(buffer.AddMotionTo(3 * kSecond, OdometryNoiseOptions(), kExtrapolation, &none));
  EXPECT_EQ(none.pose(), Eigen::Vector3d::Zero());
  EXPECT_EQ(none.noise(), Eigen::Matrix4d::Zero());
}

TEST(ScanPredictionTest, WithoutOdometryTheRobotStandsStillWithTheExtrapolationNoise) {
  testing::StepScene scene;
  OdometryBuffer none;
  const Eigen::Matrix3d before = scene.state.robot_covariance();
  const PredictionNotes notes =
      PredictToScan(kSecond, ScanInterval{false, 0.5, 0.5}, scene.options, &none, &scene.state);
  EXPECT_TRUE(notes.without_odometry);
  EXPECT_FALSE(notes.time_gap);
  EXPECT_EQ(scene.state.robot_pose(), Eigen::Vector3d::Zero());
  const double rate = scene.options.extrapolation_speed_sigma_mps *
                      scene.options.extrapolation_speed_sigma_mps;
  EXPECT_NEAR(scene.state.robot_covariance()(0, 0), before(0, 0) + rate * 0.25, 1e-12);
  // The first scan predicts nothing and misses nothing.
  testing::StepScene first;
  EXPECT_FALSE(PredictToScan(kSecond, ScanInterval{true, 0.0, 0.0}, first.options, &none,
                             &first.state)
                   .without_odometry);
}

TEST(ScanPredictionTest, AGapInflatesTheRobotAndTheMoversAndMoversMove) {
  testing::StepScene scene;
  const int mover = scene.AddMover({2.0, 0.0}, 0.1, {1.0, 0.5}, 0.1);
  const int landmark = scene.AddLandmark({0.0, 3.0}, 0.1);
  OdometryBuffer odometry;
  odometry.Add(Reading(0, 0.0, 0.0, 0.0));
  odometry.Add(Reading(2 * kSecond, 0.0, 0.0, 0.0));
  const int v = scene.state.object(mover).velocity_index;
  const double velocity_var = scene.state.covariance()(v, v);
  const PredictionNotes notes = PredictToScan(
      2 * kSecond, ScanInterval{false, 2.0, 2.0}, scene.options, &odometry, &scene.state);
  EXPECT_TRUE(notes.time_gap);
  EXPECT_FALSE(notes.without_odometry);
  EXPECT_NEAR((scene.state.position(mover) - Eigen::Vector2d(4.0, 1.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(scene.state.position(landmark), Eigen::Vector2d(0.0, 3.0));
  const double gap_velocity = scene.options.gap_mover_velocity_sigma_mps;
  EXPECT_GT(scene.state.covariance()(v, v), velocity_var + gap_velocity * gap_velocity - 1e-9);
  const double position_sigma = scene.options.gap_robot_position_sigma_mps * 2.0;
  EXPECT_GT(scene.state.robot_covariance()(0, 0), position_sigma * position_sigma);
  // The gap's heading sigma is at most pi, however long the gap (here with odometry covering
  // it, so that no extrapolation noise adds to it).
  testing::StepScene long_gap;
  OdometryBuffer standing;
  standing.Add(Reading(0, 0.0, 0.0, 0.0));
  standing.Add(Reading(10000 * kSecond, 0.0, 0.0, 0.0));
  PredictToScan(10000 * kSecond, ScanInterval{false, 1e4, 30.0}, long_gap.options, &standing,
                &long_gap.state);
  EXPECT_GT(long_gap.state.robot_covariance()(2, 2), M_PI * M_PI);
  EXPECT_LT(long_gap.state.robot_covariance()(2, 2), M_PI * M_PI + 0.1);
}

}  // namespace
}  // namespace slammtt
