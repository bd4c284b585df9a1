// common/angle.h: WrapAngle's range, its boundaries, non-finite input, and that it gives, bit for
// bit, what each of the project's earlier wrap functions gave (the world's and the drivers'
// remainder form, the metrics' fmod form, the segmenter's subtract-once form), so that replacing
// them changed no output.
#include "common/angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace slammtt {
namespace {

// The earlier implementations, as they were written (tools/world/planar_pose.cc,
// drivers/rplidar/rplidar_beams.cc and drivers/p3dx/p3dx_odometry.cc; tools/metrics/pose2.cc;
// estimator/angle.h; perception/segmenter.cc).
double RemainderForm(double a) {
  double wrapped = std::remainder(a, 2.0 * M_PI);
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

double FmodForm(double a) {
  const double two_pi = 2.0 * M_PI;
  double wrapped = std::fmod(a, two_pi);
  if (wrapped <= -M_PI) wrapped += two_pi;
  if (wrapped > M_PI) wrapped -= two_pi;
  return wrapped;
}

// estimator/angle.h before it included common/angle.h.
double EstimatorForm(double a) {
  if (!std::isfinite(a)) return a;
  if (std::abs(a) <= M_PI) return a <= -M_PI ? a + 2.0 * M_PI : a;
  double wrapped = std::remainder(a, 2.0 * M_PI);
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

double SubtractOnceForm(double a) {
  if (a > -M_PI && a <= M_PI) return a;
  const double two_pi = 2.0 * M_PI;
  if (a > M_PI && a <= 3.0 * M_PI) {
    a -= two_pi;
  } else if (a <= -M_PI && a > -3.0 * M_PI) {
    a += two_pi;
  } else {
    a = std::remainder(a, two_pi);
  }
  if (a <= -M_PI) a += two_pi;
  if (a > M_PI) a -= two_pi;
  return a;
}

uint64_t Bits(double x) {
  uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof(bits));
  return bits;
}

// Angles that probe every branch: around each multiple of pi up to +-40 pi (the last doubles
// before and after it), zeros, tiny and huge values, and a seeded uniform sample.
std::vector<double> ProbeAngles() {
  std::vector<double> angles = {0.0, -0.0, 1e-300, -1e-300, 0.25, -0.25, 1e6, -1e6, 1e15, -1e300};
  for (int k = -40; k <= 40; ++k) {
    const double a = k * M_PI;
    for (const double x : {a, std::nextafter(a, -1e9), std::nextafter(a, 1e9)}) {
      angles.push_back(x);
    }
  }
  std::mt19937_64 rng(20240607);
  std::uniform_real_distribution<double> near(-20.0, 20.0);
  std::uniform_real_distribution<double> far(-1e5, 1e5);
  for (int i = 0; i < 100000; ++i) angles.push_back(i % 2 == 0 ? near(rng) : far(rng));
  return angles;
}

TEST(WrapAngleTest, BoundariesOfTheHalfOpenRange) {
  EXPECT_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_EQ(WrapAngle(3.0 * M_PI), M_PI);
  EXPECT_EQ(WrapAngle(0.25), 0.25);
  EXPECT_EQ(WrapAngle(-0.25), -0.25);
  EXPECT_NEAR(WrapAngle(-0.5 * M_PI - 4.0 * M_PI), -0.5 * M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(3.0 * M_PI + 0.1), -M_PI + 0.1, 1e-12);
  EXPECT_GT(WrapAngle(std::nextafter(-M_PI, 0.0)), -M_PI);
}

TEST(WrapAngleTest, EveryResultIsInTheRangeAndDiffersByWholeTurns) {
  for (const double a : ProbeAngles()) {
    const double w = WrapAngle(a);
    ASSERT_GT(w, -M_PI) << a;
    ASSERT_LE(w, M_PI) << a;
    const double turns = (a - w) / (2.0 * M_PI);
    ASSERT_NEAR(turns, std::round(turns), 1e-9 * std::max(1.0, std::abs(turns))) << a;
  }
}

TEST(WrapAngleTest, NonFiniteInputIsReturnedUnchanged) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(WrapAngle(inf), inf);
  EXPECT_EQ(WrapAngle(-inf), -inf);
  EXPECT_TRUE(std::isnan(WrapAngle(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(EstimatorForm(inf), inf);
}

TEST(WrapAngleTest, BitForBitTheSameAsTheEarlierImplementationsOnFiniteInput) {
  const std::vector<double> angles = ProbeAngles();
  for (const double a : angles) {
    const uint64_t wrapped = Bits(WrapAngle(a));
    ASSERT_EQ(wrapped, Bits(RemainderForm(a))) << a;
    ASSERT_EQ(wrapped, Bits(FmodForm(a))) << a;
    ASSERT_EQ(wrapped, Bits(EstimatorForm(a))) << a;
    // The one exception: the segmenter's form gave +0 for exactly -2 pi (-2pi + 2pi), remainder
    // gives -0 (the sign of x); equal as numbers.
    if (a == -2.0 * M_PI) continue;
    ASSERT_EQ(wrapped, Bits(SubtractOnceForm(a))) << a;
  }
  EXPECT_EQ(Bits(WrapAngle(-2.0 * M_PI)), Bits(-0.0));
  EXPECT_EQ(Bits(WrapAngle(2.0 * M_PI)), Bits(0.0));
  EXPECT_EQ(WrapAngle(-3.0 * M_PI), M_PI);
  EXPECT_EQ(Bits(SubtractOnceForm(-2.0 * M_PI)), Bits(0.0));
}

}  // namespace
}  // namespace slammtt
