// The standard server information packet (SIP) of the P3-DX microcontroller and the name
// packet that answers SYNC2: parsing with bound checks (host side) and encoding (emulator side).
//
// Standard SIP payload, little-endian (Pioneer 3 Operations Manual 2006, ARCOS Table 4
// "ARCOS standard SIP contents"; trailing fields after the sonar readings as ARIA
// ArRobot::processMotorPacket() reads them):
//   type 0x32 (motors stopped) / 0x33 (robot moving)      1
//   XPOS, YPOS  15-bit wrapping position counters           2 + 2
//   THPOS       heading, 4096 units per revolution          2 (signed; modulo 4096)
//   L VEL, R VEL wheel velocities [mm/s before VelConvFactor] 2 + 2 (signed)
//   BATTERY     tenths of volts                             1
//   STALL AND BUMPERS bit 0 left stall, 1-7 left bumpers,   2
//               bit 8 right stall, 9-15 right bumpers
//   CONTROL     heading servo setpoint                      2 (signed)
//   FLAGS       bit 0 motors enabled, 1-4 sonar arrays, 5 STOP button, 6 E_stall, ...
//                                                           2 (Table 8 "The FLAGS bits")
//   COMPASS     2-degree units                              1
//   SONAR COUNT n, then n x (number 1, range 2)             1 + 3n
//   optional, newer firmware, each group only when all its bytes are there:
//   GRIP_STATE 1, ANPORT 1, ANALOG 1, DIGIN 1, DIGOUT 1     5
//   BATTERYX10  tenths of volts                             2
//   CHARGESTATE                                             1
//   ROTVEL      rotational velocity [0.1 deg/s]             2 (signed)
//   FAULTFLAGS                                              2
// Later fields (lateral velocity, temperature, ...) are ignored.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace slammtt {

inline constexpr uint8_t kP3dxSipStopped = 0x32;
inline constexpr uint8_t kP3dxSipMoving = 0x33;
inline constexpr uint8_t kP3dxNamePacket = 0x02;  // the reply to SYNC2

struct P3dxSonarReading {
  uint8_t number = 0;
  uint16_t range = 0;  // mm before RangeConvFactor (1.0 on the P3-DX)
};

struct P3dxSipIo {
  uint8_t grip_state = 0;
  uint8_t analog_port = 0;
  uint8_t analog = 0;
  uint8_t digital_in = 0;
  uint8_t digital_out = 0;
};

struct P3dxStandardSip {
  bool moving = false;         // type 0x33
  uint16_t x_pos = 0;          // 0..32767 (the top bit is masked off when parsing)
  uint16_t y_pos = 0;
  int16_t th_pos = 0;          // as sent; the heading is th_pos modulo 4096 units
  int16_t left_vel = 0;        // mm/s before VelConvFactor
  int16_t right_vel = 0;
  uint8_t battery_decivolts = 0;
  uint16_t stall_and_bumpers = 0;
  int16_t control = 0;
  uint16_t flags = 0;
  uint8_t compass = 0;
  std::vector<P3dxSonarReading> sonars;
  std::optional<P3dxSipIo> io;
  std::optional<uint16_t> battery_decivolts_x10;  // BATTERYX10, tenths of volts
  std::optional<uint8_t> charge_state;
  std::optional<int16_t> rot_vel_decideg_per_s;   // ROTVEL, 0.1 deg/s
  std::optional<uint16_t> fault_flags;

  bool left_wheel_stalled() const { return (stall_and_bumpers & 0x0001) != 0; }
  bool right_wheel_stalled() const { return (stall_and_bumpers & 0x0100) != 0; }
  // Bits 0-6 left bumpers, bits 8-14 right bumpers (the base_status_t layout).
  int bumpers() const {
    return ((stall_and_bumpers >> 1) & 0x7F) | (((stall_and_bumpers >> 9) & 0x7F) << 8);
  }
  bool motors_enabled() const { return (flags & 0x0001) != 0; }
  // The better battery reading: BATTERYX10 when the firmware sends it, else BATTERY.
  double battery_v() const {
    return battery_decivolts_x10 ? *battery_decivolts_x10 * 0.1 : battery_decivolts * 0.1;
  }
};

enum class P3dxSipStatus {
  kOk,
  kNotSip,   // the type byte is not 0x32/0x33
  kShort,    // fewer bytes than the mandatory fields and the announced sonar readings
};

struct P3dxSipParse {
  P3dxSipStatus status = P3dxSipStatus::kNotSip;
  P3dxStandardSip sip;  // meaningful only with kOk
};

// True for the type bytes of a standard SIP.
inline bool IsP3dxSipType(uint8_t type) {
  return type == kP3dxSipStopped || type == kP3dxSipMoving;
}

// Parses a SIP payload (type byte first, as P3dxPacketDecoder returns it). Never reads past the
// payload; an incomplete optional group is left out.
P3dxSipParse ParseP3dxStandardSip(const std::vector<uint8_t>& payload);

// The payload of a SIP (emulator side). Optional groups are written up to the last one that is
// set; an unset group before it goes out as zeros. At most 60 sonar readings.
std::vector<uint8_t> EncodeP3dxStandardSip(const P3dxStandardSip& sip);

// What the robot says about itself in its reply to SYNC2: id 0x02, then three NUL-terminated
// strings: name, class ("Pioneer"), subclass ("p3dx", "p3dx-sh", ...).
struct P3dxRobotIdentity {
  std::string name;
  std::string robot_class;
  std::string subclass;  // lower-cased when parsed (ARIA does the same)
};

// nullopt when the payload is not a name packet (id other than 0x02). A string whose terminator
// is missing ends at the end of the payload; missing strings are empty.
std::optional<P3dxRobotIdentity> ParseP3dxRobotIdentity(const std::vector<uint8_t>& payload);
std::vector<uint8_t> EncodeP3dxRobotIdentity(const P3dxRobotIdentity& identity);

}  // namespace slammtt
