#include "tools/metrics/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace slammtt {
namespace {

TEST(Pose2Test, WrapsAnglesIntoTheHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(WrapAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(-0.5 * M_PI - 4 * M_PI), -0.5 * M_PI, 1e-12);
  EXPECT_DOUBLE_EQ(WrapAngle(0.25), 0.25);
}

TEST(Pose2Test, ComposeWithInverseIsIdentity) {
  const Pose2 a{1.5, -2.0, 2.5};
  const Pose2 id = Compose(a, Inverse(a));
  EXPECT_NEAR(id.x_m, 0.0, 1e-12);
  EXPECT_NEAR(id.y_m, 0.0, 1e-12);
  EXPECT_NEAR(id.heading_rad, 0.0, 1e-12);
  // A quarter turn maps x onto y.
  const Eigen::Vector2d p = TransformPoint(Pose2{1, 2, M_PI / 2}, Eigen::Vector2d(1, 0));
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  const Eigen::Matrix2d c = RotateCovariance(Pose2{0, 0, M_PI / 2},
                                             Eigen::Vector2d(4.0, 1.0).asDiagonal());
  EXPECT_NEAR(c(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(c(1, 1), 4.0, 1e-12);
}

TEST(Pose2Test, AnchorTakesTheEstimateFrameOntoTheTruth) {
  const Pose2 truth{3.0, 4.0, 0.5};
  const Pose2 estimate{0.0, 0.0, 0.0};  // the estimator's map frame starts at its start pose
  const Pose2 anchor = AnchorTransform(truth, estimate);
  const Pose2 anchored = Compose(anchor, estimate);
  EXPECT_NEAR(anchored.x_m, 3.0, 1e-12);
  EXPECT_NEAR(anchored.y_m, 4.0, 1e-12);
  EXPECT_NEAR(anchored.heading_rad, 0.5, 1e-12);
  // One metre ahead in the estimate's frame is one metre along heading 0.5 in the truth frame.
  const Eigen::Vector2d ahead = TransformPoint(anchor, Eigen::Vector2d(1, 0));
  EXPECT_NEAR(ahead.x(), 3.0 + std::cos(0.5), 1e-12);
  EXPECT_NEAR(ahead.y(), 4.0 + std::sin(0.5), 1e-12);
}

TEST(Pose2Test, InterpolatesAlongTheShortArcAndNeverExtrapolates) {
  const double deg = M_PI / 180.0;
  const std::vector<TimedPose> trajectory = {{0, Pose2{0, 0, 170 * deg}},
                                             {10, Pose2{10, 2, -170 * deg}},
                                             {20, Pose2{10, 4, -170 * deg}}};
  const auto mid = InterpolatePose(trajectory, 5);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->x_m, 5.0, 1e-12);
  EXPECT_NEAR(mid->y_m, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(mid->heading_rad), M_PI, 1e-9);  // through 180, not through 0
  const auto exact = InterpolatePose(trajectory, 20);
  ASSERT_TRUE(exact.has_value());
  EXPECT_DOUBLE_EQ(exact->y_m, 4.0);
  EXPECT_FALSE(InterpolatePose(trajectory, -1).has_value());
  EXPECT_FALSE(InterpolatePose(trajectory, 21).has_value());
  EXPECT_FALSE(InterpolatePose({}, 0).has_value());
}

TEST(TrajectoryErrorTest, HandComputedErrors) {
  std::vector<PosePair> pairs = {{0, Pose2{0, 0, 0}, Pose2{0, 0, 0}},
                                 {1, Pose2{1, 0, 0}, Pose2{1, 3, 0.1}},
                                 {2, Pose2{2, 0, 0}, Pose2{6, 0, -0.2}}};
  const TrajectoryError e = EvaluateTrajectory(pairs);
  EXPECT_EQ(e.count, 3);
  EXPECT_DOUBLE_EQ(e.rmse_m, std::sqrt((0.0 + 9.0 + 16.0) / 3.0));
  EXPECT_DOUBLE_EQ(e.mean_m, 7.0 / 3.0);
  EXPECT_DOUBLE_EQ(e.max_m, 4.0);
  EXPECT_EQ(e.max_utime, 2);
  EXPECT_DOUBLE_EQ(e.final_position_error_m, 4.0);
  EXPECT_DOUBLE_EQ(e.final_heading_error_rad, -0.2);
  EXPECT_EQ(e.position_error_m, (std::vector<double>{0.0, 3.0, 4.0}));
}

TEST(TrajectoryErrorTest, AnchoringRemovesAConstantFrameOffset) {
  // The estimate is the truth seen from a frame rotated by 90 degrees and shifted.
  const Pose2 frame{5.0, -1.0, M_PI / 2};
  std::vector<PosePair> pairs;
  for (int k = 0; k < 5; ++k) {
    const Pose2 truth{0.5 * k, 0.1 * k * k, 0.2 * k};
    pairs.push_back({k, truth, Compose(Inverse(frame), truth)});
  }
  const Pose2 anchor = AnchorAtFirstPair(&pairs);
  EXPECT_NEAR(anchor.heading_rad, M_PI / 2, 1e-12);
  const TrajectoryError e = EvaluateTrajectory(pairs);
  EXPECT_NEAR(e.max_m, 0.0, 1e-9);
  EXPECT_NEAR(e.final_heading_error_rad, 0.0, 1e-12);
}

TEST(TrajectoryErrorTest, EmptyInputAndNonFinitePoses) {
  const TrajectoryError e = EvaluateTrajectory({});
  EXPECT_EQ(e.count, 0);
  EXPECT_EQ(e.rmse_m, 0.0);
  std::vector<PosePair> none;
  const Pose2 anchor = AnchorAtFirstPair(&none);
  EXPECT_EQ(anchor.x_m, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(EvaluateTrajectory({{0, Pose2{}, Pose2{nan, 0, 0}}}), std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
