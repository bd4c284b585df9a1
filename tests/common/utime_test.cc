// common/utime.h: the same bits as the int64 expression it replaces wherever that one is
// defined, and a finite, correctly signed value where it is not (overflow).
#include "common/utime.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>

namespace slammtt {
namespace {

TEST(UtimeTest, SameBitsAsTheIntegerDifferenceForRealUtimes) {
  std::mt19937_64 rng(7);
  // Utimes of this century and of the simulated worlds (from 0), gaps up to a day.
  std::uniform_int_distribution<int64_t> base(0, int64_t{4102444800} * 1000000);  // to 2100
  std::uniform_int_distribution<int64_t> gap(-int64_t{86400} * 1000000, int64_t{86400} * 1000000);
  for (int k = 0; k < 100000; ++k) {
    const int64_t earlier = base(rng);
    const int64_t later = earlier + gap(rng);
    const double old_seconds = 1e-6 * static_cast<double>(later - earlier);
    ASSERT_EQ(SecondsBetween(later, earlier), old_seconds) << later << " " << earlier;
    ASSERT_EQ(MicrosecondsBetween(later, earlier), static_cast<double>(later - earlier));
  }
}

TEST(UtimeTest, EndsOfTheRangeDoNotOverflow) {
  const int64_t lowest = std::numeric_limits<int64_t>::min();
  const int64_t highest = std::numeric_limits<int64_t>::max();
  // 2^64 - 1 us apart: the int64 difference would wrap to -1.
  EXPECT_GT(SecondsBetween(highest, lowest), 1.8e13);
  EXPECT_LT(SecondsBetween(lowest, highest), -1.8e13);
  EXPECT_GT(SecondsBetween(1100000, lowest + 5), 9.2e12);
  EXPECT_EQ(SecondsBetween(highest, highest), 0.0);
}

}  // namespace
}  // namespace slammtt
