// Options of the RPLIDAR driver (`rplidar:` section of the stack configuration, read by
// rplidar_driver_config.h; --port, --baud and --mode on the command line win). Defaults are the
// A2M8's (datasheet, SDK). Pure: the device session (rplidar_session.h) checks them in its
// constructor (CheckRplidarSessionOptions).
//
// VisitRplidarDriverOptions lists every option once (key, range, doc; common/options_schema.h):
// the reader of the `rplidar:` section, the check and the table of docs/rplidar.md ("Options",
// printed by slammtt-rplidar --options-table) come from it.
#pragma once

#include <string>

#include "common/options_schema.h"

#include "drivers/rplidar/rplidar_beams.h"
#include "drivers/rplidar/rplidar_scan_decoder.h"

namespace slammtt {
namespace rplidar {

enum class ScanMode { kStandard, kExpress };
// How the motor is started: auto asks GET_ACC_BOARD_FLAG (A2/A3) and uses SET_MOTOR_PWM when
// the accessory board takes it, the DTR line otherwise; none leaves the motor alone.
enum class MotorControl { kAuto, kDtr, kPwm, kNone };

const char* ScanModeName(ScanMode mode);

struct RplidarDriverOptions {
  std::string port = "/dev/ttyUSB0";  // serial device path or tcp://HOST:PORT
  int baud = 115200;                  // A2M8; A2M7/A2M12: 256000
  ScanMode scan_mode = ScanMode::kExpress;  // express: 4000 samples/s (~0.9 deg at 10 Hz)
  bool force_scan = false;            // standard mode: FORCE_SCAN instead of SCAN
  MotorControl motor_control = MotorControl::kAuto;
  int motor_pwm = kDefaultMotorPwm;   // 0..1023, with the accessory board
  BeamConversionOptions beams;
  StandardDecoderOptions decoder;
  int connect_timeout_ms = 2000;      // TCP connect
  int response_timeout_ms = 1000;     // a single reply (GET_INFO, GET_HEALTH, ...)
  int first_data_timeout_ms = 5000;   // scan request to first data (motor spin-up)
  int data_timeout_ms = 1000;         // silence while scanning before the link is reopened
  int reset_wait_ms = 2000;           // RESET to the next request (the device reboots)
  int reconnect_initial_ms = 200;     // backoff between reopen attempts, doubling ...
  int reconnect_max_ms = 5000;        // ... up to this
  double status_period_s = 1.0;       // LIDAR_STATUS period (also sent on every change)
  // Where the scanner sits on the robot (paper eq. 11: a, b, from the middle of the wheel
  // axle, x forward, y left) and the heading of the scans' frame (after angle_offset_deg), CCW
  // from the robot's: published on LASER_GEOMETRY with LIDAR_STATUS, so that the estimator
  // takes them from here (docs/estimator.md, "Laser geometry").
  double mount_forward_m = 0.0;
  double mount_left_m = 0.0;
  double mount_yaw_deg = 0.0;
};

// "standard" / "express"; std::invalid_argument otherwise.
ScanMode ParseScanMode(const std::string& text);

// The options schema of the driver, in the order of RplidarDriverOptions. Keys are the field
// names; the fields of `beams` and `decoder` are keys of their own, without the struct's name
// (angle_offset_deg, max_step_deg), as the section always wrote them. The decoder's confirm_run
// and lookahead are not options (the decoder's design, rplidar_scan_decoder.h).
void VisitRplidarDriverOptions(OptionVisitor* visitor, RplidarDriverOptions* options);

// Empty when the session can run with the options; otherwise one line naming the first bad
// option by its key ("motor_pwm = 2000: must be in [0, 1023]"): each value within its range (the
// schema), then range_max_m > range_min_m and reconnect_max_ms >= reconnect_initial_ms. The
// port is not judged here: the session opens it through its injected factory (the program checks
// it with CheckEndpoint before, rplidar_driver_config.h).
std::string CheckRplidarSessionOptions(const RplidarDriverOptions& options);

// The Markdown table of every key of the `rplidar:` section (docs/rplidar.md, "Options").
std::string RplidarDriverOptionsTable();

}  // namespace rplidar
}  // namespace slammtt
