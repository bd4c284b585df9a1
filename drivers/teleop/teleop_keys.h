// Keyboard teleop of slammtt-teleop, pure: the bytes a terminal in raw mode sends for a key,
// and how each key changes the command.
//   up / w      faster forward (or slower backward) by linear_step_mps
//   down / s    slower forward (or faster backward)
//   left / a    turn more to the left (CCW) by angular_step_radps
//   right / d   turn more to the right
//   space       stop (both speeds 0)
//   q, Ctrl-C, Ctrl-D   quit
// Arrows arrive as ESC [ A..D (ESC O A..D in the terminal's application mode).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace slammtt {

enum class TeleopKey { kFaster, kSlower, kLeft, kRight, kStop, kQuit };

class TerminalKeyDecoder {
 public:
  // The keys in `bytes`, in order; other bytes and escape sequences are ignored. An escape
  // sequence cut between two calls is completed by the next call.
  std::vector<TeleopKey> Feed(const uint8_t* bytes, size_t size);

 private:
  std::string escape_;  // an escape sequence begun and not finished
};

struct TeleopCommand {
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

struct TeleopSteps {
  double linear_step_mps = 0.05;
  double angular_step_radps = 0.1;
  double max_linear_mps = 0.5;      // config/robot.yaml p3dx.max_linear_mps
  double max_angular_radps = 1.0;   // and max_angular_radps
};

// The command after `key` (kQuit leaves it as it is: the caller stops the robot as it quits).
// Speeds stay within +-max; a step that comes within half a step of 0 lands on 0 exactly.
TeleopCommand ApplyTeleopKey(const TeleopCommand& command, TeleopKey key,
                             const TeleopSteps& steps);

}  // namespace slammtt
