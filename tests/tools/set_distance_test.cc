#include "tools/metrics/set_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace slammtt {
namespace {

constexpr double kC = 1.0;  // cut-off of the evaluation [m]
constexpr double kP = 2.0;  // order
constexpr double kAlpha = 2.0;

Eigen::Vector2d P(double x, double y) { return Eigen::Vector2d(x, y); }

TEST(SetDistanceTest, BothEmptyIsZero) {
  EXPECT_EQ(Ospa({}, {}, kC, kP).distance_m, 0.0);
  const GospaResult g = Gospa({}, {}, kC, kP, kAlpha);
  EXPECT_EQ(g.distance_m, 0.0);
  EXPECT_EQ(g.num_missed + g.num_false + g.num_assigned, 0);
}

TEST(SetDistanceTest, AllMissed) {
  const PointSet truth = {P(0, 0), P(3, 0), P(6, 0)};
  const OspaResult o = Ospa(truth, {}, kC, kP);
  EXPECT_DOUBLE_EQ(o.distance_m, kC);  // pure cardinality error
  EXPECT_DOUBLE_EQ(o.cardinality_m, kC);
  EXPECT_DOUBLE_EQ(o.localisation_m, 0.0);
  const GospaResult g = Gospa(truth, {}, kC, kP, kAlpha);
  EXPECT_DOUBLE_EQ(g.distance_m, std::sqrt(3 * 0.5));  // c^p / 2 per miss
  EXPECT_EQ(g.num_missed, 3);
  EXPECT_EQ(g.num_false, 0);
}

TEST(SetDistanceTest, AllFalse) {
  const PointSet estimate = {P(1, 1), P(2, 2)};
  EXPECT_DOUBLE_EQ(Ospa({}, estimate, kC, kP).distance_m, kC);
  const GospaResult g = Gospa({}, estimate, kC, kP, kAlpha);
  EXPECT_DOUBLE_EQ(g.distance_m, 1.0);  // sqrt(2 * 1/2)
  EXPECT_EQ(g.num_false, 2);
  EXPECT_EQ(g.num_missed, 0);
}

TEST(SetDistanceTest, OnePairWithinCutoff) {
  const OspaResult o = Ospa({P(0, 0)}, {P(0.3, 0.4)}, kC, kP);
  EXPECT_DOUBLE_EQ(o.distance_m, 0.5);
  const GospaResult g = Gospa({P(0, 0)}, {P(0.3, 0.4)}, kC, kP, kAlpha);
  EXPECT_DOUBLE_EQ(g.distance_m, 0.5);
  EXPECT_EQ(g.num_assigned, 1);
  EXPECT_DOUBLE_EQ(g.localisation_pow, 0.25);
}

TEST(SetDistanceTest, PairBeyondCutoffIsOneMissAndOneFalse) {
  const OspaResult o = Ospa({P(0, 0)}, {P(3, 0)}, kC, kP);
  EXPECT_DOUBLE_EQ(o.distance_m, 1.0);  // min(3, c) = c
  const GospaResult g = Gospa({P(0, 0)}, {P(3, 0)}, kC, kP, kAlpha);
  EXPECT_DOUBLE_EQ(g.distance_m, 1.0);  // sqrt(1/2 + 1/2)
  EXPECT_EQ(g.num_assigned, 0);
  EXPECT_EQ(g.num_missed, 1);
  EXPECT_EQ(g.num_false, 1);
}

TEST(SetDistanceTest, MixedCardinalityHandComputed) {
  // Truth {(0,0), (10,0)}, estimate {(0.3,0.4)}: one pair at 0.5 m and one miss.
  const PointSet truth = {P(0, 0), P(10, 0)};
  const PointSet estimate = {P(0.3, 0.4)};
  const OspaResult o = Ospa(truth, estimate, kC, kP);
  EXPECT_DOUBLE_EQ(o.distance_m, std::sqrt((0.25 + 1.0) / 2.0));
  EXPECT_DOUBLE_EQ(o.localisation_m, std::sqrt(0.25 / 2.0));
  EXPECT_DOUBLE_EQ(o.cardinality_m, std::sqrt(1.0 / 2.0));
  const GospaResult g = Gospa(truth, estimate, kC, kP, kAlpha);
  EXPECT_DOUBLE_EQ(g.distance_m, std::sqrt(0.25 + 0.5));
  EXPECT_EQ(g.num_assigned, 1);
  EXPECT_EQ(g.num_missed, 1);
  EXPECT_EQ(g.num_false, 0);
}

TEST(SetDistanceTest, UsesTheOptimalNotTheGreedyAssignment) {
  // Greedy nearest pair first: (1,0)-(0.6,0) then (0,0)-(1.7,0): 0.16 + 2.89 = 3.05.
  // Optimal: (0,0)-(0.6,0) and (1,0)-(1.7,0): 0.36 + 0.49 = 0.85.
  const double c = 5.0;
  const OspaResult o = Ospa({P(0, 0), P(1, 0)}, {P(0.6, 0), P(1.7, 0)}, c, kP);
  EXPECT_NEAR(o.distance_m, std::sqrt(0.85 / 2.0), 1e-12);
  const GospaResult g = Gospa({P(0, 0), P(1, 0)}, {P(0.6, 0), P(1.7, 0)}, c, kP, kAlpha);
  EXPECT_NEAR(g.distance_m, std::sqrt(0.85), 1e-12);
}

TEST(SetDistanceTest, OrderOneAndAlphaOne) {
  // p = 1: OSPA is the mean cut-off distance per object.
  const OspaResult o = Ospa({P(0, 0), P(5, 0)}, {P(0.2, 0)}, kC, 1.0);
  EXPECT_DOUBLE_EQ(o.distance_m, (0.2 + 1.0) / 2.0);
  // alpha = 1 charges c^p (not c^p / 2) per cardinality mismatch.
  const GospaResult g = Gospa({P(0, 0), P(5, 0)}, {P(0.2, 0)}, kC, 1.0, 1.0);
  EXPECT_DOUBLE_EQ(g.distance_m, 0.2 + 1.0);
}

TEST(SetDistanceTest, SymmetricInItsArguments) {
  const PointSet a = {P(0, 0), P(2, 1), P(4, 4)};
  const PointSet b = {P(0.5, 0), P(4, 3.8)};
  EXPECT_DOUBLE_EQ(Ospa(a, b, kC, kP).distance_m, Ospa(b, a, kC, kP).distance_m);
  EXPECT_DOUBLE_EQ(Gospa(a, b, kC, kP, kAlpha).distance_m,
                   Gospa(b, a, kC, kP, kAlpha).distance_m);
}

TEST(SetDistanceTest, RejectsBadParametersAndNonFinitePoints) {
  EXPECT_THROW(Ospa({}, {}, 0.0, kP), std::invalid_argument);
  EXPECT_THROW(Ospa({}, {}, kC, 0.5), std::invalid_argument);
  EXPECT_THROW(Gospa({}, {}, kC, kP, 3.0), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Ospa({P(nan, 0)}, {}, kC, kP), std::invalid_argument);
  EXPECT_THROW(Gospa({}, {P(0, nan)}, kC, kP, kAlpha), std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
