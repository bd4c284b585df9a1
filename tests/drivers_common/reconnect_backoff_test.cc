#include "drivers/common/reconnect_backoff.h"

#include <gtest/gtest.h>

namespace slammtt {
namespace {

TEST(ReconnectBackoffTest, DoublesUpToTheCeilingAndResets) {
  ReconnectBackoff backoff(100, 1000);
  EXPECT_EQ(backoff.NextDelayMs(), 100);
  EXPECT_EQ(backoff.NextDelayMs(), 200);
  EXPECT_EQ(backoff.NextDelayMs(), 400);
  EXPECT_EQ(backoff.NextDelayMs(), 800);
  EXPECT_EQ(backoff.NextDelayMs(), 1000);
  EXPECT_EQ(backoff.NextDelayMs(), 1000);
  EXPECT_EQ(backoff.failures(), 6);
  backoff.Reset();
  EXPECT_EQ(backoff.failures(), 0);
  EXPECT_EQ(backoff.NextDelayMs(), 100);
}

TEST(ReconnectBackoffTest, CeilingBelowInitialUsesInitial) {
  ReconnectBackoff backoff(500, 100);
  EXPECT_EQ(backoff.NextDelayMs(), 500);
  EXPECT_EQ(backoff.NextDelayMs(), 500);
}

}  // namespace
}  // namespace slammtt
