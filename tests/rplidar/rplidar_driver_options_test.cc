#include "drivers/rplidar/rplidar_driver_config.h"

#include <gtest/gtest.h>

#include <stdexcept>

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
