// The p3dx: section of the stack configuration: defaults, every key, and mistakes named with the
// file, the line and the key.
#include "drivers/p3dx/p3dx_driver_config.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/p3dx/p3dx_session.h"
#include "simulated_robot_link.h"
#include "tests/support/options_table.h"

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
  ExpectConfigError("  command_authentication: hmac\n",
                    "p3dx.command_authentication: expected hmac-sha256 or none, got 'hmac'");
  ExpectConfigError("  command_max_age_s: 0\n", "command_max_age_s");
  ExpectConfigError("  command_max_age_s: 61\n", "command_max_age_s");
}

// A condition between options is reported at the line of the key it names.
TEST(P3dxDriverOptionsTest, ConditionsNameTheLineOfTheirKey) {
  ExpectConfigError("  reconnect_initial_s: 2\n  reconnect_max_s: 1\n",
                    "robot.yaml:3: p3dx.reconnect_max_s: must not be less than "
                    "reconnect_initial_s");
  ExpectConfigError("  pulse_interval_s: 2\n",
                    "robot.yaml:2: p3dx.pulse_interval_s: must be in (0, 2), got 2");
}

// The schema names every key once, the reader reads every one (a section setting each key to its
// default gives the defaults), and docs/p3dx.md carries the generated table.
TEST(P3dxDriverOptionsTest, EveryKeyOfTheSchemaIsReadAndDocumented) {
  const std::string table = P3dxDriverOptionsTable();
  const std::vector<testing::OptionsTableRow> rows = testing::ParseOptionsTable(table);
  ASSERT_EQ(rows.size(), 17u) << table;
  EXPECT_TRUE(testing::KeysAreUnique(rows));
  const Config config =
      Config::FromString(testing::SectionOfDefaults("p3dx", rows), "every.yaml");
  const P3dxDriverOptions o = ReadP3dxDriverOptions(config.Child("p3dx"));
  const P3dxDriverOptions d;
  EXPECT_EQ(o.port, d.port);
  EXPECT_EQ(o.baud, d.baud);
  EXPECT_EQ(o.max_angular_radps, d.max_angular_radps);
  EXPECT_EQ(o.pulse_interval_s, d.pulse_interval_s);
  EXPECT_EQ(o.subclass, d.subclass);
  EXPECT_EQ(o.command_authentication, d.command_authentication);
  EXPECT_EQ(o.command_key_file, d.command_key_file);
  EXPECT_EQ(o.command_max_age_s, d.command_max_age_s);
  const std::string docs = testing::ReadCheckoutFile("docs/p3dx.md");
  ASSERT_FALSE(docs.empty()) << "docs/p3dx.md is part of the checkout";
  EXPECT_NE(docs.find(table), std::string::npos)
      << "docs/p3dx.md: replace the options table by `slammtt-p3dx --options-table`";
}

// The session refuses options the schema or a condition refuses, naming the key; the defaults
// and the shipped robot's options are accepted.
TEST(P3dxDriverOptionsTest, TheSessionChecksItsOptions) {
  EXPECT_EQ(CheckP3dxDriverOptions(P3dxDriverOptions()), "");
  SimulatedClock clock;
  struct NoOutput : P3dxSessionOutput {
    void OnBaseOdometry(const BaseOdometry&) override {}
    void OnBaseStatus(const BaseStatus&) override {}
  } output;
  const auto never_opened = [](const std::string&, int) -> std::unique_ptr<ByteStream> {
    return nullptr;
  };
  const auto refused = [&](const P3dxDriverOptions& options, const std::string& needle) {
    try {
      P3dxSession session(options, never_opened, &clock, &output, nullptr);
      ADD_FAILURE() << "accepted, expected " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  P3dxDriverOptions o;
  o.max_linear_mps = 2.5;
  refused(o, "max_linear_mps = 2.5: must be in (0, 2]");
  o = P3dxDriverOptions();
  o.sync_attempts = 0;
  refused(o, "sync_attempts");
  o = P3dxDriverOptions();
  o.reconnect_max_s = 0.1;
  refused(o, "reconnect_max_s must not be less than reconnect_initial_s");
  o = P3dxDriverOptions();
  o.subclass = "p3at";
  refused(o, "p3at");
  o = P3dxDriverOptions();
  o.command_max_age_s = std::nan("");
  refused(o, "command_max_age_s");
}

// --port, --baud, --max-linear-mps, --max-angular-radps, --command-timeout-s: declared from the
// schema, held to its ranges, winning over the configuration.
TEST(P3dxDriverOptionsTest, TheCommandLineSetsItsKeysWithinTheirRanges) {
  const auto parse = [](std::vector<const char*> args) {
    auto command_line = std::make_unique<CommandLine>("slammtt-p3dx", "[options]", "test");
    AddP3dxDriverOptions(command_line.get());
    args.insert(args.begin(), "slammtt-p3dx");
    command_line->Parse(static_cast<int>(args.size()), args.data());
    return command_line;
  };
  P3dxDriverOptions o;
  ApplyP3dxDriverCommandLine(*parse({"--port", "tcp://10.0.0.3:4002", "--baud", "19200",
                                     "--max-linear-mps", "0.3", "--max-angular-radps", "0.8",
                                     "--command-timeout-s", "0.25"}),
                             &o);
  EXPECT_EQ(o.port, "tcp://10.0.0.3:4002");
  EXPECT_EQ(o.baud, 19200);
  EXPECT_EQ(o.max_linear_mps, 0.3);
  EXPECT_EQ(o.max_angular_radps, 0.8);
  EXPECT_EQ(o.command_timeout_s, 0.25);
  const auto usage_error = [&](std::vector<const char*> args, const std::string& needle) {
    P3dxDriverOptions options;
    try {
      ApplyP3dxDriverCommandLine(*parse(args), &options);
      ADD_FAILURE() << "accepted, expected " << needle;
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  usage_error({"--max-linear-mps", "3"}, "--max-linear-mps: must be in (0, 2], got 3");
  usage_error({"--baud", "4294976896"}, "--baud: must be in [1, 1e+07], got 4294976896");
  usage_error({"--port", "ttyUSB0"}, "ttyUSB0");
  usage_error({"--command-timeout-s", "fast"}, "--command-timeout-s");
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
