#include "drivers/rplidar/rplidar_driver_config.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/rplidar/rplidar_session.h"
#include "rplidar_test_support.h"
#include "tests/support/options_table.h"

namespace slammtt {
namespace rplidar {
namespace {

TEST(RplidarDriverOptionsTest, DefaultsAreTheA2M8s) {
  const Config config = Config::FromString("rplidar: {}\n");
  const Config section = config.Child("rplidar");
  const RplidarDriverOptions options = ReadRplidarDriverOptions(section);
  section.CheckUnused();
  EXPECT_EQ(options.port, "/dev/ttyUSB0");
  EXPECT_EQ(options.baud, 115200);
  EXPECT_EQ(options.scan_mode, ScanMode::kExpress);
  EXPECT_EQ(options.motor_control, MotorControl::kAuto);
  EXPECT_EQ(options.motor_pwm, 660);
  EXPECT_DOUBLE_EQ(options.beams.range_min_m, 0.15);
  EXPECT_DOUBLE_EQ(options.beams.range_max_m, 12.0);
}

TEST(RplidarDriverOptionsTest, ReadsEveryKey) {
  const Config config = Config::FromString(
      "rplidar:\n  port: tcp://10.0.0.2:4001\n  baud: 256000\n  scan_mode: standard\n"
      "  force_scan: true\n  motor_control: pwm\n  motor_pwm: 500\n  angle_offset_deg: 180\n"
      "  upside_down: true\n  range_min_m: 0.2\n  range_max_m: 16\n  max_step_deg: 10\n"
      "  max_back_step_deg: 2\n  connect_timeout_ms: 300\n  response_timeout_ms: 400\n"
      "  first_data_timeout_ms: 3000\n  data_timeout_ms: 700\n  reset_wait_ms: 900\n"
      "  reconnect_initial_ms: 100\n  reconnect_max_ms: 800\n  status_period_s: 0.5\n"
      "  mount_forward_m: 0.12\n  mount_left_m: -0.03\n  mount_yaw_deg: 90\n");
  const Config section = config.Child("rplidar");
  const RplidarDriverOptions options = ReadRplidarDriverOptions(section);
  EXPECT_NO_THROW(section.CheckUnused());
  EXPECT_EQ(options.port, "tcp://10.0.0.2:4001");
  EXPECT_EQ(options.baud, 256000);
  EXPECT_EQ(options.scan_mode, ScanMode::kStandard);
  EXPECT_TRUE(options.force_scan);
  EXPECT_EQ(options.motor_control, MotorControl::kPwm);
  EXPECT_EQ(options.motor_pwm, 500);
  EXPECT_DOUBLE_EQ(options.beams.angle_offset_deg, 180.0);
  EXPECT_TRUE(options.beams.upside_down);
  EXPECT_DOUBLE_EQ(options.decoder.max_step_deg, 10.0);
  EXPECT_EQ(options.reconnect_max_ms, 800);
  EXPECT_DOUBLE_EQ(options.status_period_s, 0.5);
  EXPECT_EQ(options.mount_forward_m, 0.12);
  EXPECT_EQ(options.mount_left_m, -0.03);
  EXPECT_EQ(options.mount_yaw_deg, 90.0);
  EXPECT_NO_THROW(CheckRplidarDriverOptions(options));
}

void ExpectConfigError(const std::string& yaml, const std::string& needle) {
  const Config config = Config::FromString("rplidar:\n" + yaml, "robot.yaml");
  const Config section = config.Child("rplidar");
  try {
    ReadRplidarDriverOptions(section);
    section.CheckUnused();
    FAIL() << "accepted: " << yaml;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("robot.yaml:"), std::string::npos) << e.what();
  }
}

TEST(RplidarDriverOptionsTest, BadValuesNameTheKey) {
  ExpectConfigError("  scan_mode: turbo\n", "rplidar.scan_mode");
  ExpectConfigError("  motor_control: maybe\n", "rplidar.motor_control");
  ExpectConfigError("  motor_pwm: 2000\n", "rplidar.motor_pwm");
  ExpectConfigError("  baud: -1\n", "rplidar.baud");
  ExpectConfigError("  range_min_m: 5\n  range_max_m: 1\n", "rplidar.range_max_m");
  ExpectConfigError("  reconnect_initial_ms: 500\n  reconnect_max_ms: 100\n", "reconnect_max_ms");
  ExpectConfigError("  max_step_deg: 0\n", "rplidar.max_step_deg");
  ExpectConfigError("  prot: /dev/ttyUSB0\n", "rplidar.prot");
  ExpectConfigError("  status_period_s: 0\n", "rplidar.status_period_s");
  ExpectConfigError("  status_period_s: 1e300\n", "rplidar.status_period_s");  // no overflow
  ExpectConfigError("  baud: 4294967297\n", "rplidar.baud");  // 2^32 + 1: not 1 when narrowed
  // Before: taken, and every beam angle became what is left of 1e300 - angle in a double.
  ExpectConfigError("  angle_offset_deg: 1e300\n", "rplidar.angle_offset_deg");
  ExpectConfigError("  angle_offset_deg: -360.5\n", "rplidar.angle_offset_deg");
  ExpectConfigError("  mount_forward_m: 12\n", "rplidar.mount_forward_m");
  ExpectConfigError("  mount_left_m: .nan\n", "rplidar.mount_left_m");
  ExpectConfigError("  mount_yaw_deg: 181\n", "rplidar.mount_yaw_deg");
}

// A condition between options is reported at the line of the key it names.
TEST(RplidarDriverOptionsTest, ConditionsNameTheLineOfTheirKey) {
  ExpectConfigError("  range_min_m: 5\n  range_max_m: 1\n",
                    "robot.yaml:3: rplidar.range_max_m: must be > range_min_m");
  ExpectConfigError("  motor_pwm: 2000\n",
                    "robot.yaml:2: rplidar.motor_pwm: must be in [0, 1023], got 2000");
}

// The schema names every key once, the reader reads every one (a section setting each key to its
// default gives the defaults), and docs/rplidar.md carries the generated table.
TEST(RplidarDriverOptionsTest, EveryKeyOfTheSchemaIsReadAndDocumented) {
  const std::string table = RplidarDriverOptionsTable();
  const std::vector<slammtt::testing::OptionsTableRow> rows =
      slammtt::testing::ParseOptionsTable(table);
  ASSERT_EQ(rows.size(), 23u) << table;
  EXPECT_TRUE(slammtt::testing::KeysAreUnique(rows));
  const Config config =
      Config::FromString(slammtt::testing::SectionOfDefaults("rplidar", rows), "every.yaml");
  const RplidarDriverOptions o = ReadRplidarDriverOptions(config.Child("rplidar"));
  const RplidarDriverOptions d;
  EXPECT_EQ(o.port, d.port);
  EXPECT_EQ(o.scan_mode, d.scan_mode);
  EXPECT_EQ(o.motor_control, d.motor_control);
  EXPECT_EQ(o.beams.range_min_m, d.beams.range_min_m);
  EXPECT_EQ(o.decoder.max_back_step_deg, d.decoder.max_back_step_deg);
  EXPECT_EQ(o.reconnect_max_ms, d.reconnect_max_ms);
  EXPECT_EQ(o.mount_yaw_deg, d.mount_yaw_deg);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/rplidar.md");
  ASSERT_FALSE(docs.empty()) << "docs/rplidar.md is part of the checkout";
  EXPECT_NE(docs.find(table), std::string::npos)
      << "docs/rplidar.md: replace the options table by `slammtt-rplidar --options-table`";
}

// The session refuses options the schema or a condition refuses, naming the key.
TEST(RplidarDriverOptionsTest, TheSessionChecksItsOptions) {
  EXPECT_EQ(CheckRplidarSessionOptions(RplidarDriverOptions()), "");
  testing_support::VirtualClock clock;
  struct NoOutput : RplidarSessionOutput {
    void OnLaserScan(const LaserScan&) override {}
    void OnLidarStatus(const LidarStatus&) override {}
  } output;
  const auto refused = [&](const RplidarDriverOptions& options, const std::string& needle) {
    try {
      RplidarSession session(
          options, []() -> std::unique_ptr<ByteStream> { return nullptr; }, &clock, &output,
          nullptr);
      ADD_FAILURE() << "accepted, expected " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  RplidarDriverOptions o;
  o.motor_pwm = -1;
  refused(o, "motor_pwm = -1: must be in [0, 1023]");
  o = RplidarDriverOptions();
  o.beams.range_max_m = 0.1;
  refused(o, "range_max_m must be > range_min_m");
  o = RplidarDriverOptions();
  o.reconnect_initial_ms = 9000;
  refused(o, "reconnect_max_ms must be at least reconnect_initial_ms");
  o = RplidarDriverOptions();
  o.decoder.max_step_deg = 180;
  refused(o, "max_step_deg");
}

// --port and --baud from the schema, --mode for scan_mode; they win over the configuration.
TEST(RplidarDriverOptionsTest, TheCommandLineSetsItsKeysWithinTheirRanges) {
  const auto apply = [](std::vector<const char*> args, RplidarDriverOptions* options) {
    CommandLine command_line("slammtt-rplidar", "[options]", "test");
    AddRplidarDriverOptions(&command_line);
    args.insert(args.begin(), "slammtt-rplidar");
    command_line.Parse(static_cast<int>(args.size()), args.data());
    ApplyRplidarDriverCommandLine(command_line, options);
  };
  RplidarDriverOptions o;
  apply({"--port", "tcp://10.0.0.2:4001", "--baud", "256000", "--mode", "standard"}, &o);
  EXPECT_EQ(o.port, "tcp://10.0.0.2:4001");
  EXPECT_EQ(o.baud, 256000);
  EXPECT_EQ(o.scan_mode, ScanMode::kStandard);
  EXPECT_THROW(apply({"--baud", "0"}, &o), UsageError);
  EXPECT_THROW(apply({"--mode", "turbo"}, &o), UsageError);
}

TEST(RplidarDriverOptionsTest, MalformedPortIsRefusedBeforeAnyOpen) {
  RplidarDriverOptions options;
  options.port = "ttyUSB0";
  EXPECT_THROW(CheckRplidarDriverOptions(options), std::invalid_argument);
  options.port = "tcp://robot";
  EXPECT_THROW(CheckRplidarDriverOptions(options), std::invalid_argument);
  EXPECT_EQ(ParseScanMode("express"), ScanMode::kExpress);
  EXPECT_THROW(ParseScanMode("fast"), std::invalid_argument);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
