#include "drivers/rplidar/rplidar_driver_options.h"

#include <stdexcept>

namespace slammtt {
namespace rplidar {

const char* ScanModeName(ScanMode mode) {
  return mode == ScanMode::kExpress ? "express" : "standard";
}

ScanMode ParseScanMode(const std::string& text) {
  if (text == "standard") return ScanMode::kStandard;
  if (text == "express") return ScanMode::kExpress;
  throw std::invalid_argument("scan mode must be standard or express, got \"" + text + "\"");
}

void VisitRplidarDriverOptions(OptionVisitor* v, RplidarDriverOptions* o) {
  using R = OptionRange;
  const R milliseconds = R::Between(1, 1000000000);
  v->String("port", &o->port,
            "serial port (udev aliases resolved) or `tcp://HOST:PORT` (ser2net, docs/drivers.md)");
  v->Int("baud", &o->baud, R::Between(1, 1000000000), "serial rate: A2M8; A2M7 and A2M12: 256000");
  int scan_mode = static_cast<int>(o->scan_mode);
  v->Choice("scan_mode", &scan_mode, {"standard", "express"},
            "`express`: 4000 samples/s (about 0.9 degree at 10 Hz); `standard`: 2000");
  o->scan_mode = static_cast<ScanMode>(scan_mode);
  v->Bool("force_scan", &o->force_scan, "standard mode: FORCE_SCAN instead of SCAN");
  int motor_control = static_cast<int>(o->motor_control);
  v->Choice("motor_control", &motor_control, {"auto", "dtr", "pwm", "none"},
            "`auto`: GET_ACC_BOARD_FLAG chooses `pwm` or `dtr`; `none`: the motor is left alone");
  o->motor_control = static_cast<MotorControl>(motor_control);
  v->Int("motor_pwm", &o->motor_pwm, R::Between(0, 1023),
         "motor duty with the accessory board (the SDK's default for the A2)");
  // A mount yaw is within a turn either way; a huge value would leave nothing of the beam angle
  // after the subtraction in double.
  v->Double("angle_offset_deg", &o->beams.angle_offset_deg, R::Between(-360, 360),
            "where the device's 0 points in the sensor frame, CCW from x");
  v->Bool("upside_down", &o->beams.upside_down, "the device is mounted upside down");
  v->Double("range_min_m", &o->beams.range_min_m, R::AtLeast(0),
            "nearer samples are invalid (A2 datasheet)");
  v->Double("range_max_m", &o->beams.range_max_m, R::Above(0),
            "farther samples are invalid (A2M8 datasheet; A2M12: 16)");
  v->Double("max_step_deg", &o->decoder.max_step_deg, R::Open(0, 180),
            "standard decoder: forward angle step allowed between consecutive samples");
  v->Double("max_back_step_deg", &o->decoder.max_back_step_deg, R{0, 180, true, false},
            "standard decoder: backward step allowed (angles of real samples jitter)");
  v->Int("connect_timeout_ms", &o->connect_timeout_ms, milliseconds, "TCP connect");
  v->Int("response_timeout_ms", &o->response_timeout_ms, milliseconds,
         "a single reply (GET_INFO, GET_HEALTH, ...), a write");
  v->Int("first_data_timeout_ms", &o->first_data_timeout_ms, milliseconds,
         "scan request to the first sample (motor spin-up)");
  v->Int("data_timeout_ms", &o->data_timeout_ms, milliseconds,
         "silence while scanning before the link is reopened");
  v->Int("reset_wait_ms", &o->reset_wait_ms, milliseconds,
         "RESET to the next request (the device reboots)");
  v->Int("reconnect_initial_ms", &o->reconnect_initial_ms, milliseconds,
         "first reopen delay, doubling ...");
  v->Int("reconnect_max_ms", &o->reconnect_max_ms, milliseconds, "... up to this");
  // Becomes microseconds in int64_t: an hour is far beyond any sensible period.
  v->Double("status_period_s", &o->status_period_s, R::AboveUpTo(0, 3600),
            "LIDAR_STATUS period (also sent on every change)");
  // A scanner on a robot of a few metres at most: anything beyond is a typo.
  v->Double("mount_forward_m", &o->mount_forward_m, R::Between(-10, 10),
            "the scanner's centre ahead of the axle centre (paper eq. 11: a)");
  v->Double("mount_left_m", &o->mount_left_m, R::Between(-10, 10), "...left of it (b)");
  v->Double("mount_yaw_deg", &o->mount_yaw_deg, R::Between(-180, 180),
            "heading of the scans' frame (after `angle_offset_deg`), CCW from the robot's");
}

std::string CheckRplidarSessionOptions(const RplidarDriverOptions& options) {
  RplidarDriverOptions o = options;
  OptionRangeCheck check;
  VisitRplidarDriverOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  if (!(o.beams.range_max_m > o.beams.range_min_m)) return "range_max_m must be > range_min_m";
  if (o.reconnect_max_ms < o.reconnect_initial_ms) {
    return "reconnect_max_ms must be at least reconnect_initial_ms";
  }
  return "";
}

std::string RplidarDriverOptionsTable() {
  RplidarDriverOptions defaults;
  OptionsMarkdownTable table;
  VisitRplidarDriverOptions(&table, &defaults);
  return table.Table();
}

}  // namespace rplidar
}  // namespace slammtt
