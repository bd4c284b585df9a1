#include "drivers/rplidar/rplidar_driver_config.h"

#include <cmath>
#include <stdexcept>

#include "drivers/common/byte_stream.h"

namespace slammtt {
namespace rplidar {
namespace {

int ReadPositiveInt(const Config& section, const std::string& key, int fallback) {
  const int64_t value = section.GetInt(key, fallback);
  if (value <= 0 || value > 1000000000) section.FailKey(key, "must be a positive integer");
  return static_cast<int>(value);
}

MotorControl ParseMotorControl(const Config& section, const std::string& text) {
  if (text == "auto") return MotorControl::kAuto;
  if (text == "dtr") return MotorControl::kDtr;
  if (text == "pwm") return MotorControl::kPwm;
  if (text == "none") return MotorControl::kNone;
  section.FailKey("motor_control", "expected auto, dtr, pwm or none, got \"" + text + "\"");
}

}  // namespace

RplidarDriverOptions ReadRplidarDriverOptions(const Config& section) {
  RplidarDriverOptions options;
  options.port = section.GetString("port", options.port);
  options.baud = ReadPositiveInt(section, "baud", options.baud);
  const std::string mode = section.GetString("scan_mode", ScanModeName(options.scan_mode));
  try {
    options.scan_mode = ParseScanMode(mode);
  } catch (const std::invalid_argument& e) {
    section.FailKey("scan_mode", e.what());
  }
  options.force_scan = section.GetBool("force_scan", options.force_scan);
  options.motor_control = ParseMotorControl(section, section.GetString("motor_control", "auto"));
  const int64_t pwm = section.GetInt("motor_pwm", options.motor_pwm);
  if (pwm < 0 || pwm > 1023) section.FailKey("motor_pwm", "must be within 0..1023");
  options.motor_pwm = static_cast<int>(pwm);
  options.beams.angle_offset_deg = section.GetDouble("angle_offset_deg", 0.0);
  // A mount yaw is within a turn either way; a huge value would leave nothing of the beam
  // angle after the subtraction in double.
  if (!(std::abs(options.beams.angle_offset_deg) <= 360.0)) {
    section.FailKey("angle_offset_deg", "must be within [-360, 360] degrees");
  }
  options.beams.upside_down = section.GetBool("upside_down", false);
  options.beams.range_min_m = section.GetDouble("range_min_m", options.beams.range_min_m);
  options.beams.range_max_m = section.GetDouble("range_max_m", options.beams.range_max_m);
  if (options.beams.range_min_m < 0.0 || options.beams.range_max_m <= options.beams.range_min_m) {
    section.FailKey("range_max_m", "needs 0 <= range_min_m < range_max_m");
  }
  options.decoder.max_step_deg = section.GetDouble("max_step_deg", options.decoder.max_step_deg);
  options.decoder.max_back_step_deg =
      section.GetDouble("max_back_step_deg", options.decoder.max_back_step_deg);
  if (options.decoder.max_step_deg <= 0.0 || options.decoder.max_step_deg >= 180.0) {
    section.FailKey("max_step_deg", "must be within (0, 180)");
  }
  if (options.decoder.max_back_step_deg < 0.0 || options.decoder.max_back_step_deg >= 180.0) {
    section.FailKey("max_back_step_deg", "must be within [0, 180)");
  }
  options.connect_timeout_ms = ReadPositiveInt(section, "connect_timeout_ms", options.connect_timeout_ms);
  options.response_timeout_ms =
      ReadPositiveInt(section, "response_timeout_ms", options.response_timeout_ms);
  options.first_data_timeout_ms =
      ReadPositiveInt(section, "first_data_timeout_ms", options.first_data_timeout_ms);
  options.data_timeout_ms = ReadPositiveInt(section, "data_timeout_ms", options.data_timeout_ms);
  options.reset_wait_ms = ReadPositiveInt(section, "reset_wait_ms", options.reset_wait_ms);
  options.reconnect_initial_ms =
      ReadPositiveInt(section, "reconnect_initial_ms", options.reconnect_initial_ms);
  options.reconnect_max_ms = ReadPositiveInt(section, "reconnect_max_ms", options.reconnect_max_ms);
  if (options.reconnect_max_ms < options.reconnect_initial_ms) {
    section.FailKey("reconnect_max_ms", "must be at least reconnect_initial_ms");
  }
  options.mount_forward_m = section.GetDouble("mount_forward_m", options.mount_forward_m);
  options.mount_left_m = section.GetDouble("mount_left_m", options.mount_left_m);
  // A scanner on a robot of a few metres at most: anything beyond is a typo.
  if (!(std::abs(options.mount_forward_m) <= 10.0)) {
    section.FailKey("mount_forward_m", "must be within [-10, 10] m");
  }
  if (!(std::abs(options.mount_left_m) <= 10.0)) {
    section.FailKey("mount_left_m", "must be within [-10, 10] m");
  }
  options.mount_yaw_deg = section.GetDouble("mount_yaw_deg", options.mount_yaw_deg);
  if (!(std::abs(options.mount_yaw_deg) <= 180.0)) {
    section.FailKey("mount_yaw_deg", "must be within [-180, 180] degrees");
  }
  options.status_period_s = section.GetDouble("status_period_s", options.status_period_s);
  // Becomes microseconds in int64_t: an hour is far beyond any sensible period.
  if (options.status_period_s <= 0.0 || options.status_period_s > 3600.0) {
    section.FailKey("status_period_s", "must be within (0, 3600] s");
  }
  return options;
}

void CheckRplidarDriverOptions(const RplidarDriverOptions& options) {
  CheckEndpoint(options.port, options.baud);
  if (options.motor_pwm < 0 || options.motor_pwm > 1023) {
    throw std::invalid_argument("motor PWM must be within 0..1023");
  }
}

}  // namespace rplidar
}  // namespace slammtt
