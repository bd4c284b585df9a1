#include "drivers/teleop/teleop_keys.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

namespace {

constexpr uint8_t kEscape = 0x1B;

bool ArrowKey(char final_byte, TeleopKey* key) {
  switch (final_byte) {
    case 'A': *key = TeleopKey::kFaster; return true;
    case 'B': *key = TeleopKey::kSlower; return true;
    case 'C': *key = TeleopKey::kRight; return true;
    case 'D': *key = TeleopKey::kLeft; return true;
    default: return false;
  }
}

bool PlainKey(uint8_t byte, TeleopKey* key) {
  switch (byte) {
    case 'w': case 'W': *key = TeleopKey::kFaster; return true;
    case 's': case 'S': *key = TeleopKey::kSlower; return true;
    case 'a': case 'A': *key = TeleopKey::kLeft; return true;
    case 'd': case 'D': *key = TeleopKey::kRight; return true;
    case ' ': *key = TeleopKey::kStop; return true;
    case 'q': case 'Q': case 0x03: case 0x04: *key = TeleopKey::kQuit; return true;
    default: return false;
  }
}

double Step(double value, double step, double limit) {
  const double next = std::clamp(value + step, -limit, limit);
  return std::abs(next) < 0.5 * std::abs(step) ? 0.0 : next;
}

}  // namespace

std::vector<TeleopKey> TerminalKeyDecoder::Feed(const uint8_t* bytes, size_t size) {
  std::vector<TeleopKey> keys;
  for (size_t i = 0; i < size; ++i) {
    const uint8_t byte = bytes[i];
    TeleopKey key = TeleopKey::kStop;
    if (!escape_.empty()) {
      escape_.push_back(static_cast<char>(byte));
      if (escape_.size() == 2) {
        if (byte != '[' && byte != 'O') escape_.clear();  // not a key sequence: dropped
        continue;
      }
      // CSI: parameter bytes 0x30-0x3F, then a final byte 0x40-0x7E ends the sequence.
      if (byte >= 0x30 && byte <= 0x3F) continue;
      const bool plain_arrow = escape_.size() == 3;
      escape_.clear();
      if (plain_arrow && ArrowKey(static_cast<char>(byte), &key)) keys.push_back(key);
      continue;
    }
    if (byte == kEscape) {
      escape_.push_back(static_cast<char>(byte));
    } else if (PlainKey(byte, &key)) {
      keys.push_back(key);
    }
  }
  return keys;
}

TeleopCommand ApplyTeleopKey(const TeleopCommand& command, TeleopKey key,
                             const TeleopSteps& steps) {
  TeleopCommand next = command;
  switch (key) {
    case TeleopKey::kFaster:
      next.linear_mps = Step(command.linear_mps, steps.linear_step_mps, steps.max_linear_mps);
      break;
    case TeleopKey::kSlower:
      next.linear_mps = Step(command.linear_mps, -steps.linear_step_mps, steps.max_linear_mps);
      break;
    case TeleopKey::kLeft:
      next.angular_radps =
          Step(command.angular_radps, steps.angular_step_radps, steps.max_angular_radps);
      break;
    case TeleopKey::kRight:
      next.angular_radps =
          Step(command.angular_radps, -steps.angular_step_radps, steps.max_angular_radps);
      break;
    case TeleopKey::kStop:
      next = TeleopCommand{};
      break;
    case TeleopKey::kQuit:
      break;
  }
  return next;
}

}  // namespace slammtt
