#include "runtime/channels.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "runtime/command_line.h"
#include "runtime/lcm_io.h"

namespace slammtt {
namespace {

TEST(ChannelsTest, DefaultsConfigAndOverrides) {
  Channels channels;
  EXPECT_EQ(channels.Get("features"), "FEATURES");
  channels.ApplyConfig(Config::FromString("features: F2\nodometry: ODOM\n", "c.yaml"));
  EXPECT_EQ(channels.Get("features"), "F2");
  channels.ApplyOverrides({"features=F3"});
  EXPECT_EQ(channels.Get("features"), "F3");
  EXPECT_EQ(channels.Get("odometry"), "ODOM");
}

TEST(ChannelsTest, UnknownKeysAreErrors) {
  Channels channels;
  EXPECT_THROW(channels.ApplyConfig(Config::FromString("featurs: F\n", "c.yaml")), ConfigError);
  EXPECT_THROW(channels.ApplyOverrides({"featurs=F"}), UsageError);
  EXPECT_THROW(channels.ApplyOverrides({"features"}), UsageError);
  EXPECT_THROW(channels.ApplyOverrides({"features="}), UsageError);
}

TEST(LcmUrlTest, PrecedenceIsCommandLineConfigEnvironmentDefault) {
  unsetenv("LCM_DEFAULT_URL");
  EXPECT_EQ(ResolveLcmUrl(std::nullopt, std::nullopt), kDefaultLcmUrl);
  setenv("LCM_DEFAULT_URL", "memq://", 1);
  EXPECT_EQ(ResolveLcmUrl(std::nullopt, std::nullopt), "memq://");
  EXPECT_EQ(ResolveLcmUrl(std::nullopt, std::string("file:///x")), "file:///x");
  EXPECT_EQ(ResolveLcmUrl(std::string("udpm://239.1.1.1:7000?ttl=0"), std::string("x")),
            "udpm://239.1.1.1:7000?ttl=0");
  unsetenv("LCM_DEFAULT_URL");
}

}  // namespace
}  // namespace slammtt
