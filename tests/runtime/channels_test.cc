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

// Before: a 64-byte name was taken, and LCM drops every message on such a channel.
TEST(ChannelsTest, NamesLcmCannotCarryAreErrors) {
  Channels channels;
  const std::string longest(63, 'F');
  channels.ApplyOverrides({"features=" + longest});
  EXPECT_EQ(channels.Get("features"), longest);
  const std::string too_long(64, 'F');
  try {
    channels.ApplyOverrides({"features=" + too_long});
    ADD_FAILURE() << "accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("channel name of 64 bytes; LCM carries at most 63"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(channels.ApplyConfig(Config::FromString("pose: " + too_long + "\n", "c.yaml")),
               ConfigError);
  EXPECT_THROW(channels.ApplyOverrides({"pose=PO\tSE"}), UsageError);
  EXPECT_THROW(channels.ApplyConfig(Config::FromString("pose: ''\n", "c.yaml")), ConfigError);
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
