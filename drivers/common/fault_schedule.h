// The fault schedules of the device emulators: "KIND@SECONDS[:ARG]" on their command lines
// (`--fault disconnect@10:2`), a fault of KIND injected SECONDS after the emulator started,
// with an optional argument whose meaning the emulator gives (bytes, packets, seconds, flags).
// Pure: the caller says how long the emulator has run; FaultSchedule says which faults are due.
#pragma once

#include <cstddef>
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

// When the faults of a schedule fire: each once, at the first TakeDue() whose elapsed time has
// reached its time. How long a fault lasts (a silence of 3 s) is the emulator's: it is given the
// fault when it fires and ends it itself.
class FaultSchedule {
 public:
  // The faults' times, seconds after the start, in the order the faults were given.
  explicit FaultSchedule(std::vector<double> at_s);
  // The indices (into the times given) of the faults due at `elapsed_s` seconds after the start
  // that have not fired yet, in the order they were given (not by time: two faults due at one
  // call fire in command-line order). Each index is returned by one call only.
  std::vector<size_t> TakeDue(double elapsed_s);
  // Faults that have not fired yet.
  size_t pending() const { return pending_; }

 private:
  std::vector<double> at_s_;
  std::vector<bool> fired_;
  size_t pending_;
};

}  // namespace slammtt
