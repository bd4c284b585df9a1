// The p3dx: section of the stack configuration: defaults, every key, and mistakes named with the
// file, the line and the key.
#include "drivers/p3dx/p3dx_driver_config.h"

#include <gtest/gtest.h>

#include <string>

namespace slammtt {
namespace {

TEST(P3dxDriverOptionsTest, DefaultsAreTheDocumentedOnes) {
  const Config config = Config::FromString("p3dx: {}\n");
  const Config section = config.Child("p3dx");
  const P3dxDriverOptions options = ReadP3dxDriverOptions(section);
  section.CheckUnused();
  EXPECT_EQ(options.port, "/dev/ttyUSB0");
  EXPECT_EQ(options.baud, 9600);
  EXPECT_DOUBLE_EQ(options.max_linear_mps, 0.5);
  EXPECT_DOUBLE_EQ(options.max_angular_radps, 1.0);
  EXPECT_DOUBLE_EQ(options.command_timeout_s, 0.5);
  EXPECT_DOUBLE_EQ(options.pulse_interval_s, 0.5);
  EXPECT_DOUBLE_EQ(options.sync_reply_timeout_s, 0.5);
  EXPECT_EQ(options.sync_attempts, 8);
  EXPECT_DOUBLE_EQ(options.sip_timeout_s, 1.0);
  EXPECT_DOUBLE_EQ(options.reconnect_initial_s, 0.5);
  EXPECT_DOUBLE_EQ(options.reconnect_max_s, 8.0);
  EXPECT_EQ(options.subclass, "");
  EXPECT_TRUE(options.enable_motors);
  EXPECT_DOUBLE_EQ(options.status_period_s, 1.0);
  EXPECT_EQ(options.command_authentication, P3dxDriverOptions::CommandAuthentication::kSigned);
  EXPECT_EQ(options.command_key_file, "");
  EXPECT_DOUBLE_EQ(options.command_max_age_s, 1.0);
}

TEST(P3dxDriverOptionsTest, ReadsEveryKey) {
  const Config config = Config::FromString(
      "p3dx:\n  port: tcp://10.0.0.3:4002\n  baud: 115200\n  max_linear_mps: 0.3\n"
      "  max_angular_radps: 0.7\n  command_timeout_s: 0.25\n  pulse_interval_s: 0.4\n"
      "  sync_reply_timeout_s: 0.3\n  sync_attempts: 3\n  sip_timeout_s: 0.8\n"
      "  reconnect_initial_s: 0.2\n  reconnect_max_s: 4\n  subclass: p3dx-sh\n"
      "  enable_motors: false\n  status_period_s: 2\n  command_authentication: hmac-sha256\n"
      "  command_key_file: /etc/slammtt/command.key\n  command_max_age_s: 0.5\n");
  const Config section = config.Child("p3dx");
  const P3dxDriverOptions options = ReadP3dxDriverOptions(section);
  EXPECT_NO_THROW(section.CheckUnused());
  EXPECT_EQ(options.port, "tcp://10.0.0.3:4002");
  EXPECT_EQ(options.baud, 115200);
  EXPECT_DOUBLE_EQ(options.max_linear_mps, 0.3);
  EXPECT_DOUBLE_EQ(options.max_angular_radps, 0.7);
  EXPECT_DOUBLE_EQ(options.command_timeout_s, 0.25);
  EXPECT_DOUBLE_EQ(options.pulse_interval_s, 0.4);
  EXPECT_DOUBLE_EQ(options.sync_reply_timeout_s, 0.3);
  EXPECT_EQ(options.sync_attempts, 3);
  EXPECT_DOUBLE_EQ(options.sip_timeout_s, 0.8);
  EXPECT_DOUBLE_EQ(options.reconnect_initial_s, 0.2);
  EXPECT_DOUBLE_EQ(options.reconnect_max_s, 4.0);
  EXPECT_EQ(options.subclass, "p3dx-sh");
  EXPECT_FALSE(options.enable_motors);
  EXPECT_DOUBLE_EQ(options.status_period_s, 2.0);
  EXPECT_EQ(options.command_key_file, "/etc/slammtt/command.key");
  EXPECT_DOUBLE_EQ(options.command_max_age_s, 0.5);
}

void ExpectConfigError(const std::string& yaml, const std::string& needle) {
  const Config config = Config::FromString("p3dx:\n" + yaml, "robot.yaml");
  const Config section = config.Child("p3dx");
  try {
    ReadP3dxDriverOptions(section);
    section.CheckUnused();
    FAIL() << "accepted: " << yaml;
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(needle), std::string::npos) << what;
    EXPECT_NE(what.find("robot.yaml:"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(P3dxDriverOptionsTest, MistakesNameTheKey) {
  ExpectConfigError("  speed: 3\n", "speed");
  ExpectConfigError("  port: ttyUSB0\n", "ttyUSB0");
  ExpectConfigError("  baud: 0\n", "baud");
  ExpectConfigError("  baud: 4294976896\n", "baud");  // 2^32 + 9600: not 9600 after narrowing
  ExpectConfigError("  sync_attempts: 0\n", "sync_attempts");
  ExpectConfigError("  sync_attempts: 4294967297\n", "sync_attempts");
  ExpectConfigError("  max_linear_mps: -1\n", "max_linear_mps");
  ExpectConfigError("  max_linear_mps: 3\n", "max_linear_mps");
  ExpectConfigError("  max_angular_radps: .nan\n", "max_angular_radps");
  ExpectConfigError("  command_timeout_s: 0\n", "command_timeout_s");
  ExpectConfigError("  status_period_s: 1e300\n", "status_period_s");  // no int64 overflow
  ExpectConfigError("  pulse_interval_s: 2.5\n", "pulse_interval_s");
  ExpectConfigError("  reconnect_initial_s: 2\n  reconnect_max_s: 1\n", "reconnect_max_s");
  ExpectConfigError("  subclass: p3at\n", "p3at");
  ExpectConfigError("  command_authentication: hmac\n", "must be hmac-sha256 or none");
  ExpectConfigError("  command_max_age_s: 0\n", "command_max_age_s");
  ExpectConfigError("  command_max_age_s: 61\n", "command_max_age_s");
}

// Unauthenticated commands only on a bus whose packets stay on the computer.
TEST(P3dxDriverOptionsTest, UnauthenticatedCommandsNeedALocalBus) {
  P3dxDriverOptions options;
  EXPECT_NO_THROW(CheckCommandAuthenticationForBus(options, "udpm://239.255.76.67:7667?ttl=1"));
  options.command_authentication = P3dxDriverOptions::CommandAuthentication::kNone;
  EXPECT_NO_THROW(CheckCommandAuthenticationForBus(options, "udpm://239.255.76.67:7667?ttl=0"));
  EXPECT_NO_THROW(CheckCommandAuthenticationForBus(options, "memq://"));
  EXPECT_THROW(CheckCommandAuthenticationForBus(options, "udpm://239.255.76.67:7667?ttl=1"),
               std::invalid_argument);
  EXPECT_THROW(CheckCommandAuthenticationForBus(options, "udpm://239.255.76.67:7667?ttl=abc"),
               std::invalid_argument);
  options.command_key_file = "/etc/slammtt/command.key";
  EXPECT_THROW(CheckCommandAuthenticationForBus(options, "udpm://239.255.76.67:7667?ttl=0"),
               std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
