#include "drivers/p3dx/p3dx_commands.h"

#include <algorithm>
#include <cstdlib>

#include "drivers/p3dx/p3dx_packet.h"

namespace slammtt {

std::vector<uint8_t> EncodeP3dxCommand(uint8_t command) { return FrameP3dxPacket({command}); }

std::vector<uint8_t> EncodeP3dxIntCommand(uint8_t command, int value) {
  value = std::clamp(value, -32767, 32767);
  const int magnitude = std::abs(value);
  return FrameP3dxPacket({command, value < 0 ? kP3dxArgNegative : kP3dxArgPositive,
                          static_cast<uint8_t>(magnitude & 0xFF),
                          static_cast<uint8_t>((magnitude >> 8) & 0xFF)});
}

std::vector<uint8_t> EncodeP3dxStringCommand(uint8_t command, const std::string& text) {
  const size_t length = std::min<size_t>(text.size(), 200);
  std::vector<uint8_t> payload;
  payload.reserve(3 + length);
  payload.push_back(command);
  payload.push_back(kP3dxArgString);
  payload.push_back(static_cast<uint8_t>(length));
  for (size_t i = 0; i < length; ++i) payload.push_back(static_cast<uint8_t>(text[i]));
  return FrameP3dxPacket(payload);
}

std::vector<uint8_t> EncodeP3dxVel2(int left_units, int right_units) {
  left_units = std::clamp(left_units, -127, 127);
  right_units = std::clamp(right_units, -127, 127);
  // The 16-bit pattern: high byte left, low byte right, each a two's-complement byte; read as
  // a signed 16-bit integer it goes out in sign-and-magnitude form like any integer argument.
  const uint16_t pattern = static_cast<uint16_t>(((left_units & 0xFF) << 8) | (right_units & 0xFF));
  const int value = pattern >= 0x8000 ? static_cast<int>(pattern) - 0x10000 : pattern;
  return EncodeP3dxIntCommand(p3dx_command::kVel2, value);
}

void SplitP3dxVel2(int value, int* left_units, int* right_units) {
  const uint16_t pattern = static_cast<uint16_t>(value & 0xFFFF);
  *left_units = static_cast<int8_t>(pattern >> 8);
  *right_units = static_cast<int8_t>(pattern & 0xFF);
}

std::optional<int> P3dxHostBaudIndex(int baud) {
  switch (baud) {
    case 9600: return 0;
    case 19200: return 1;
    case 38400: return 2;
    case 57600: return 3;
    case 115200: return 4;
    default: return std::nullopt;
  }
}

std::optional<P3dxClientCommand> ParseP3dxClientCommand(const std::vector<uint8_t>& payload) {
  if (payload.empty()) return std::nullopt;
  P3dxClientCommand command;
  command.number = payload[0];
  if (payload.size() == 1) return command;
  const uint8_t type = payload[1];
  if (type == kP3dxArgPositive || type == kP3dxArgNegative) {
    if (payload.size() < 4) return std::nullopt;
    const int magnitude = payload[2] | (payload[3] << 8);
    command.argument = P3dxClientCommand::Argument::kInteger;
    command.value = type == kP3dxArgNegative ? -magnitude : magnitude;
    return command;
  }
  if (type == kP3dxArgString) {
    if (payload.size() < 3) return std::nullopt;
    const size_t length = payload[2];
    if (payload.size() < 3 + length) return std::nullopt;
    command.argument = P3dxClientCommand::Argument::kString;
    command.text.assign(payload.begin() + 3, payload.begin() + 3 + static_cast<std::ptrdiff_t>(length));
    return command;
  }
  return std::nullopt;
}

}  // namespace slammtt
