// The fault schedules of the device emulators: "KIND@SECONDS[:ARG]" on their command lines
// (`--fault disconnect@10:2`), a fault of KIND injected SECONDS after the emulator started,
// with an optional argument whose meaning the emulator gives (bytes, packets, seconds, flags).
#pragma once

#include <string>
#include <vector>

namespace slammtt {

struct ScheduledFault {
  std::string kind;      // one of the emulator's fault names
  double at_s = 0.0;     // seconds after the start, >= 0
  std::string argument;  // "" when none was given
};

// Parses "KIND@SECONDS[:ARG]". Throws std::invalid_argument, one line quoting `text`, when the
// form is wrong, SECONDS is not a number from 0 to 1e6, or KIND is not in `kinds` (the message
// lists them). The argument is left to the emulator (FaultNumber, or its own form).
ScheduledFault ParseScheduledFault(const std::string& text, const std::vector<std::string>& kinds);

// A fault's numeric argument: `fallback` when empty, else a number from 0 to 1e6 (bytes,
// packets or seconds: beyond that it is a typo, and it stays far inside an int). Throws
// std::invalid_argument naming the fault (`text`) otherwise.
double FaultNumber(const std::string& argument, double fallback, const std::string& text);

}  // namespace slammtt
