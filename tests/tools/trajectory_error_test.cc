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

TEST(TrajectoryErrorTest, LeastSquaresAlignmentUndoesARigidMotionOfTheWholeEstimate) {
  // The estimate is the truth (a curve) moved by a rigid transform M: the alignment is M^-1 and
  // the aligned error vanishes, while the first-pair anchoring of a noisy start does not.
  const Pose2 motion{1.5, -2.0, 0.4};
  std::vector<PosePair> pairs;
  for (int k = 0; k < 20; ++k) {
    const Pose2 truth{0.5 * k, 0.02 * k * k, 0.1 * k};
    pairs.push_back({k, truth, Compose(motion, truth)});
  }
  const Pose2 alignment = LeastSquaresAlignment(pairs);
  const Pose2 expected = Inverse(motion);
  EXPECT_NEAR(alignment.x_m, expected.x_m, 1e-9);
  EXPECT_NEAR(alignment.y_m, expected.y_m, 1e-9);
  EXPECT_NEAR(alignment.heading_rad, expected.heading_rad, 1e-12);
  for (PosePair& p : pairs) p.estimate = Compose(alignment, p.estimate);
  EXPECT_NEAR(EvaluateTrajectory(pairs).max_m, 0.0, 1e-9);
  // Fewer than two pairs: nothing to fit.
  const Pose2 none = LeastSquaresAlignment({pairs.front()});
  EXPECT_EQ(none.x_m, 0.0);
  EXPECT_EQ(none.heading_rad, 0.0);
}

TEST(TrajectoryErrorTest, RelativePoseErrorSeesLocalJumpsNotGlobalOffsets) {
  // Truth along x at 1 m steps. An estimate offset by a rigid transform has no relative error;
  // one pose displaced by 0.1 m spoils the two steps next to it: 2 of 4 steps at 0.1 m,
  // RMSE sqrt(2 * 0.01 / 4).
  std::vector<PosePair> pairs;
  for (int k = 0; k < 5; ++k) {
    const Pose2 truth{static_cast<double>(k), 0.0, 0.0};
    pairs.push_back({k, truth, Compose(Pose2{3.0, 4.0, 1.0}, truth)});
  }
  RelativePoseError rpe = EvaluateRelativePoseError(pairs);
  EXPECT_EQ(rpe.count, 4);
  EXPECT_NEAR(rpe.translation_rmse_m, 0.0, 1e-12);
  EXPECT_NEAR(rpe.rotation_rmse_rad, 0.0, 1e-12);
  for (int k = 0; k < 5; ++k) pairs[k].estimate = pairs[k].truth;
  pairs[2].estimate.x_m += 0.1;
  rpe = EvaluateRelativePoseError(pairs);
  EXPECT_NEAR(rpe.translation_rmse_m, std::sqrt(0.02 / 4), 1e-12);
  EXPECT_NEAR(rpe.translation_max_m, 0.1, 1e-12);
  EXPECT_NEAR(rpe.translation_mean_m, 0.05, 1e-12);
  EXPECT_EQ(EvaluateRelativePoseError({}).count, 0);
}

}  // namespace
}  // namespace slammtt
