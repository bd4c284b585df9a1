// Client commands of the P3-DX microcontroller (ARCOS), encoded as whole framed packets, and the
// device-side parser the emulator uses.
//
// A command payload is the command number, then for an argument its type byte and value:
//   0x3B positive integer, 2 bytes little-endian;
//   0x1B negative integer, the absolute value in 2 bytes little-endian;
//   0x2B string, a length byte then the characters.
// Numbers and arguments: Pioneer 3 Operations Manual (2006), ARCOS "Client Commands" table;
// ARIA include/Aria/ArCommands.h. Worked examples (../shared/design/protocols/p3dx.md):
//   ENABLE 1 = FA FB 06 04 3B 01 00 05 3B,  SYNC0 = FA FB 03 00 00 00,
//   VEL2 left -5 right +10 = FA FB 06 20 1B F6 04 16 1F.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace slammtt {

// Command numbers. SYNC0/1/2 share their numbers with PULSE/OPEN/CLOSE: which one a packet is
// depends on the connection state.
namespace p3dx_command {
inline constexpr uint8_t kSync0 = 0;
inline constexpr uint8_t kSync1 = 1;
inline constexpr uint8_t kSync2 = 2;
inline constexpr uint8_t kPulse = 0;     // keeps the firmware watchdog fed
inline constexpr uint8_t kOpen = 1;      // starts the server (SIPs every SIP cycle)
inline constexpr uint8_t kClose = 2;     // ends the session, stops the robot
inline constexpr uint8_t kEnable = 4;    // int: 1 enables the motors, 0 disables them
inline constexpr uint8_t kVel = 11;      // int: translational velocity [mm/s], signed
inline constexpr uint8_t kRvel = 21;     // int: rotational velocity [deg/s], signed
inline constexpr uint8_t kStop = 29;     // stops the robot (motors stay enabled)
inline constexpr uint8_t kVel2 = 32;     // int: high byte left, low byte right wheel, in
                                         //      Vel2Divisor mm/s units, each a signed byte
inline constexpr uint8_t kHostBaud = 50; // int: 0..4 = 9600, 19200, 38400, 57600, 115200
inline constexpr uint8_t kEstop = 55;    // stops now with maximum deceleration
}  // namespace p3dx_command

// Argument type bytes.
inline constexpr uint8_t kP3dxArgPositive = 0x3B;
inline constexpr uint8_t kP3dxArgNegative = 0x1B;
inline constexpr uint8_t kP3dxArgString = 0x2B;

// A framed command without an argument (SYNC0/1/2, PULSE, OPEN, CLOSE, STOP, ESTOP).
std::vector<uint8_t> EncodeP3dxCommand(uint8_t command);
// A framed command with an integer argument; `value` is clamped to [-32767, 32767] (the range a
// sign-and-magnitude argument can carry).
std::vector<uint8_t> EncodeP3dxIntCommand(uint8_t command, int value);
// A framed command with a string argument (at most 200 characters; longer is cut).
std::vector<uint8_t> EncodeP3dxStringCommand(uint8_t command, const std::string& text);

// VEL2 from wheel speeds in Vel2Divisor units, each clamped to [-127, 127].
std::vector<uint8_t> EncodeP3dxVel2(int left_units, int right_units);
// The 16-bit VEL2 argument split back into (left, right) units, as the firmware reads it.
void SplitP3dxVel2(int value, int* left_units, int* right_units);

// HOSTBAUD's argument for a baud rate, or nullopt when ARCOS cannot switch to it.
std::optional<int> P3dxHostBaudIndex(int baud);

// A client command as the device reads it.
struct P3dxClientCommand {
  enum class Argument { kNone, kInteger, kString };
  uint8_t number = 0;
  Argument argument = Argument::kNone;
  int value = 0;       // integer argument with its sign applied
  std::string text;    // string argument
};

// Parses a command payload (from P3dxPacketDecoder). nullopt when the argument is malformed: an
// unknown type byte, fewer than 2 integer bytes, a string shorter than its length byte. A bare
// number is a command without argument; bytes after a complete argument are ignored.
std::optional<P3dxClientCommand> ParseP3dxClientCommand(const std::vector<uint8_t>& payload);

}  // namespace slammtt
