#include "perception/breakpoint_criterion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace slammtt {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(BreakpointCriterionTest, ThresholdMatchesEquation15) {
  // r sin(dtheta) / sin(lambda - dtheta) + 3 sigma, by hand: r = 2, dtheta = 1 deg, lambda = 20.
  const double expected = 2.0 * std::sin(1.0 * kDeg) / std::sin(19.0 * kDeg) + 0.09;
  EXPECT_NEAR(BreakpointThresholdM(2.0, 1.0 * kDeg, 20.0 * kDeg, 0.03), expected, 1e-15);
  EXPECT_NEAR(expected, 0.197212, 1e-6);
  // Same angle (duplicate direction): only the noise term is left.
  EXPECT_DOUBLE_EQ(BreakpointThresholdM(5.0, 0.0, 20.0 * kDeg, 0.03), 0.09);
  // At or beyond lambda no surface can join the points.
  EXPECT_TRUE(std::isinf(BreakpointThresholdM(1.0, 20.0 * kDeg, 20.0 * kDeg, 0.03)));
  EXPECT_TRUE(std::isinf(BreakpointThresholdM(1.0, 25.0 * kDeg, 20.0 * kDeg, 0.03)));
}

TEST(BreakpointCriterionTest, FastTestAgreesWithReferenceOnAGrid) {
  const double lambda = 20.0 * kDeg;
  const double sigma = 0.03;
  const BreakpointCriterion criterion(lambda, sigma, lambda);
  int splits = 0;
  int joins = 0;
  for (double r_i = 0.1; r_i < 30.0; r_i *= 1.37) {
    for (double dtheta = 0.0; dtheta < 19.9 * kDeg; dtheta += 0.173 * kDeg) {
      const double threshold = BreakpointThresholdM(r_i, dtheta, lambda, sigma);
      for (double r_j = 0.05; r_j < 40.0; r_j *= 1.11) {
        const double distance =
            std::sqrt(r_i * r_i + r_j * r_j - 2.0 * r_i * r_j * std::cos(dtheta));
        if (std::abs(distance - threshold) < 1e-9) continue;  // on the boundary itself
        const bool expected = distance > threshold;
        ASSERT_EQ(criterion.Splits(r_i, r_j, dtheta), expected)
            << "r_i " << r_i << " r_j " << r_j << " dtheta " << dtheta;
        (expected ? splits : joins) += 1;
      }
    }
  }
  // The grid exercised both outcomes.
  EXPECT_GT(splits, 1000);
  EXPECT_GT(joins, 1000);
}

TEST(BreakpointCriterionTest, AWallSeenObliquelyStaysOneButAStepSplits) {
  const BreakpointCriterion criterion(20.0 * kDeg, 0.03, 5.0 * kDeg);
  const double dtheta = 0.9 * kDeg;
  // Same range, 0.9 degrees apart at 4 m: 6 cm apart, well within the threshold.
  EXPECT_FALSE(criterion.Splits(4.0, 4.0, dtheta));
  // A person 1 m in front of a wall: a jump of 1 m splits.
  EXPECT_TRUE(criterion.Splits(4.0, 3.0, dtheta));
  // A 12 cm step at 4 m: threshold 4 sin(0.9)/sin(19.1) + 0.09 = 0.282 m; a 0.12 m step is
  // inside, a 0.35 m step is not.
  EXPECT_FALSE(criterion.Splits(4.0, 4.12, dtheta));
  EXPECT_TRUE(criterion.Splits(4.0, 4.35, dtheta));
}

TEST(BreakpointCriterionTest, GapsBeyondMaxGapOrLambdaAlwaysSplit) {
  const BreakpointCriterion criterion(20.0 * kDeg, 0.03, 5.0 * kDeg);
  EXPECT_FALSE(criterion.Splits(2.0, 2.0, 4.9 * kDeg));
  EXPECT_TRUE(criterion.Splits(2.0, 2.0, 5.0 * kDeg));
  const BreakpointCriterion no_gap_limit(20.0 * kDeg, 0.03, M_PI);
  EXPECT_FALSE(no_gap_limit.Splits(2.0, 2.0, 19.0 * kDeg));
  EXPECT_TRUE(no_gap_limit.Splits(2.0, 2.0, 20.0 * kDeg));
  EXPECT_TRUE(no_gap_limit.Splits(2.0, 2.0, M_PI));
}

}  // namespace
}  // namespace slammtt
