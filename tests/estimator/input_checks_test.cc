// The input checks of the estimator one by one: the time base of a stream (time_base.h), the
// physical plausibility of odometry (odometry_plausibility.h), the recovery of a non-finite
// state (state_recovery.h) and the feature cap (feature_validation.h).
#include <gtest/gtest.h>

#include <limits>

#include "estimator/feature_validation.h"
#include "estimator/odometry_plausibility.h"
#include "estimator/state_recovery.h"
#include "estimator/time_base.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;

TEST(StreamClockTest, OneJumpIsNeverANewTimeBase) {
  const TimeJumpLimits limits;  // 2 s either way, 3 in a row
  StreamClock clock;
  EXPECT_EQ(clock.Judge(10 * kSecond, limits), TimeVerdict::kAccept);
  EXPECT_EQ(clock.Judge(10 * kSecond + 100000, limits), TimeVerdict::kAccept);
  EXPECT_EQ(clock.Judge(-1, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(10 * kSecond + 200000, limits), TimeVerdict::kAccept);
  EXPECT_EQ(clock.jumped_in_a_row(), 0);
  EXPECT_EQ(clock.Judge(10 * kSecond + 1000000 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(10 * kSecond + 300000, limits), TimeVerdict::kAccept);
  EXPECT_EQ(*clock.newest(), 10 * kSecond + 300000);
  // Late by less than back_s: late, not a jump; a jump by more.
  EXPECT_EQ(clock.Judge(9 * kSecond, limits), TimeVerdict::kLate);
  EXPECT_EQ(clock.Judge(8 * kSecond, limits), TimeVerdict::kJumpHeld);
}

TEST(StreamClockTest, SeveralConsistentJumpedMessagesAreANewTimeBase) {
  const TimeJumpLimits limits;
  StreamClock clock;
  clock.Judge(100 * kSecond, limits);
  EXPECT_EQ(clock.Judge(1 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(1 * kSecond + 100000, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.jumped_in_a_row(), 2);
  EXPECT_EQ(clock.Judge(1 * kSecond + 200000, limits), TimeVerdict::kNewTimeBaseBack);
  EXPECT_EQ(*clock.newest(), 1 * kSecond + 200000);
  EXPECT_EQ(clock.Judge(1 * kSecond + 300000, limits), TimeVerdict::kAccept);
  // Ahead likewise.
  EXPECT_EQ(clock.Judge(500 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(500 * kSecond + 100000, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(500 * kSecond + 200000, limits), TimeVerdict::kNewTimeBaseAhead);
}

TEST(StreamClockTest, JumpedMessagesThatDisagreeAreNoEvidence) {
  const TimeJumpLimits limits;
  StreamClock clock;
  clock.Judge(100 * kSecond, limits);
  // Three jumped utimes, each far from the one before: scattered corruption, no new base.
  EXPECT_EQ(clock.Judge(1 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(50 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(-70 * kSecond, limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.Judge(std::numeric_limits<int64_t>::max(), limits), TimeVerdict::kJumpHeld);
  EXPECT_EQ(clock.jumped_in_a_row(), 1);
  EXPECT_EQ(*clock.newest(), 100 * kSecond);
  // confirm_messages = 1: every jump at once (the behaviour before issue 15).
  TimeJumpLimits at_once = limits;
  at_once.confirm_messages = 1;
  EXPECT_EQ(clock.Judge(1 * kSecond, at_once), TimeVerdict::kNewTimeBaseBack);
}

OdometryReading Reading(int64_t utime, double x_m, double heading_rad = 0.0) {
  OdometryReading r;
  r.utime = utime;
  r.pose = Eigen::Vector3d(x_m, 0.0, heading_rad);
  return r;
}

TEST(OdometryPlausibilityTest, WhatNoBaseCanReportIsRejected) {
  const OdometryPlausibilityOptions o;  // 3 m/s, 600 deg/s, 0.1 s jitter, 1e5 m
  EXPECT_EQ(OdometryReadingProblem(Reading(0, 1.0), o), "");
  EXPECT_NE(OdometryReadingProblem(Reading(0, 1e300), o).find("beyond"), std::string::npos);
  EXPECT_NE(OdometryReadingProblem(Reading(0, 1.0001e5), o), "");
  EXPECT_NE(OdometryReadingProblem(Reading(0, 0.0, 1e300), o).find("no angle"),
            std::string::npos);
  OdometryReading fast = Reading(0, 0.0);
  fast.linear_mps = -3.5;
  EXPECT_NE(OdometryReadingProblem(fast, o).find("speed"), std::string::npos);
  OdometryReading spinning = Reading(0, 0.0);
  spinning.angular_radps = 11.0;
  EXPECT_NE(OdometryReadingProblem(spinning, o).find("turn rate"), std::string::npos);
  OdometryReading nan = Reading(0, 0.0);
  nan.pose(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(OdometryReadingProblem(nan, o), "not finite");
  // Jumps: 0.1 s later, at most 3 m/s * 0.2 s = 0.6 m and 600 deg/s * 0.2 s = 2.09 rad.
  EXPECT_EQ(OdometryJumpProblem(Reading(0, 0.0), Reading(100000, 0.59), o), "");
  EXPECT_NE(OdometryJumpProblem(Reading(0, 0.0), Reading(100000, 0.61), o).find("moved"),
            std::string::npos);
  EXPECT_EQ(OdometryJumpProblem(Reading(0, 0.0), Reading(100000, 0.0, 2.0), o), "");
  EXPECT_NE(OdometryJumpProblem(Reading(0, 0.0), Reading(100000, 0.0, 2.2), o).find("turned"),
            std::string::npos);
  // The turn is judged wrapped: from 3.1 to -3.1 rad is 0.08 rad.
  EXPECT_EQ(OdometryJumpProblem(Reading(0, 0.0, 3.1), Reading(25000, 0.0, -3.1), o), "");
}

TEST(OdometryPlausibilityTest, ANewFrameNeedsSeveralConsistentReadings) {
  const OdometryPlausibilityOptions o;
  OdometryPlausibility check;
  std::string why;
  EXPECT_EQ(check.Judge(Reading(0, 100.0), o, 3, &why), OdometryVerdict::kPlausible);
  EXPECT_EQ(check.Judge(Reading(100000, 100.1), o, 3, &why), OdometryVerdict::kPlausible);
  // One reading 50 m away, then the stream goes on where it was.
  EXPECT_EQ(check.Judge(Reading(200000, 150.0), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_NE(why.find("moved"), std::string::npos);
  EXPECT_EQ(check.Judge(Reading(300000, 100.2), o, 3, &why), OdometryVerdict::kPlausible);
  // The base restarted: its pose begins again at 0 and goes on from there.
  EXPECT_EQ(check.Judge(Reading(400000, 0.0), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_EQ(check.Judge(Reading(500000, 0.05), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_EQ(check.Judge(Reading(600000, 0.1), o, 3, &why), OdometryVerdict::kNewFrame);
  EXPECT_EQ(check.Judge(Reading(700000, 0.15), o, 3, &why), OdometryVerdict::kPlausible);
  // Jumped readings that disagree with each other are no new frame.
  EXPECT_EQ(check.Judge(Reading(800000, 60.0), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_EQ(check.Judge(Reading(900000, -60.0), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_EQ(check.Judge(Reading(1000000, 60.0), o, 3, &why), OdometryVerdict::kImplausible);
  EXPECT_EQ(check.Judge(Reading(1100000, 0.2), o, 3, &why), OdometryVerdict::kPlausible);
}

SlamState StateWithThreeObjects() {
  SlamState state(Eigen::Vector3d(1.0, 2.0, 0.3), 0.01 * Eigen::Matrix3d::Identity(), 1e-4);
  const Eigen::Matrix<double, 2, 3> g = Eigen::Matrix<double, 2, 3>::Identity();
  for (int k = 0; k < 3; ++k) {
    ObjectRecord record;
    record.id = k + 1;
    state.AddObject(Eigen::Vector2d(3.0 + k, 1.0), g, 0.04 * Eigen::Matrix2d::Identity(),
                    record);
  }
  return state;
}

TEST(StateRecoveryTest, ObjectsWithNonFiniteStatesAreRemoved) {
  SlamState state = StateWithThreeObjects();
  EXPECT_TRUE(PublishedStateIsFinite(state));
  const int p = state.object(1).position_index;
  state.covariance()(p, p) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(PublishedStateIsFinite(state));
  const RecoveryOutcome outcome =
      RecoverFiniteState(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), 1e-4, &state);
  EXPECT_FALSE(outcome.robot_reset);
  EXPECT_EQ(outcome.objects_removed, 1);
  ASSERT_EQ(state.num_objects(), 2);
  EXPECT_EQ(state.object(0).record.id, 1);
  EXPECT_EQ(state.object(1).record.id, 3);
  EXPECT_TRUE(PublishedStateIsFinite(state));
  EXPECT_TRUE(state.covariance().allFinite());
  EXPECT_EQ(state.robot_pose(), Eigen::Vector3d(1.0, 2.0, 0.3));
}

TEST(StateRecoveryTest, ANonFiniteRobotStartsOverFromTheLastFinitePose) {
  SlamState state = StateWithThreeObjects();
  const int p = state.object(2).position_index;
  // A cross-covariance between the robot and an object: only a row scan finds it.
  state.covariance()(0, p) = std::numeric_limits<double>::infinity();
  state.covariance()(p, 0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(NonFiniteStates(state).empty());
  const Eigen::Vector3d last_pose(0.5, -0.5, 0.1);
  const RecoveryOutcome outcome =
      RecoverFiniteState(last_pose, 0.02 * Eigen::Matrix3d::Identity(), 1e-4, &state);
  EXPECT_TRUE(outcome.robot_reset);
  EXPECT_EQ(state.num_objects(), 0);
  EXPECT_EQ(state.robot_pose(), last_pose);
  EXPECT_EQ(state.robot_covariance(), 0.02 * Eigen::Matrix3d::Identity());
  EXPECT_TRUE(PublishedStateIsFinite(state));
}

TEST(FeatureCapTest, TheNearestFeaturesAreKeptInTheirOrder) {
  EstimatorOptions options;
  options.max_features_per_scan = 3;
  std::vector<FeatureReading> features;
  for (double range : {9.0, 2.0, 7.0, 2.0, 5.0, 1.0}) {
    FeatureReading f;
    f.range_m = range;
    f.bearing_rad = 0.1 * range;
    features.push_back(f);
  }
  const ValidatedFeatures v = ValidateFeatures(features, options);
  ASSERT_EQ(v.measurements.size(), 3u);
  EXPECT_EQ(v.over_cap, 3);
  EXPECT_EQ(v.measurements[0].range_bearing(0), 2.0);
  EXPECT_EQ(v.measurements[1].range_bearing(0), 2.0);
  EXPECT_EQ(v.measurements[2].range_bearing(0), 1.0);
  EXPECT_EQ(v.widths_m.size(), 3u);
  options.max_features_per_scan = 6;
  EXPECT_EQ(ValidateFeatures(features, options).over_cap, 0);
}

}  // namespace
}  // namespace slammtt
