// The faults slammtt-rplidar-emulator injects (docs/rplidar.md, "Emulator"), from their
// command-line form "KIND@SECONDS[:ARG]" (drivers/common/fault_schedule.h) to what the emulator
// server is asked to do. Pure: the program asks FaultSchedule which faults are due and hands each
// to its server.
#pragma once

#include <string>
#include <vector>

namespace slammtt {
namespace rplidar {

struct RplidarEmulatorFault {
  enum class Kind {
    kGarbage,      // ARG random bytes (default 100)
    kBadChecksum,  // the next ARG packets corrupted (default 1)
    kDrop,         // ARG bytes lost from the next packets (default 1)
    kSilence,      // ARG seconds without a byte either way (default 3)
    kMute,         // ARG seconds without a byte out, requests still carried out (default 3)
    kDisconnect,   // the link gone for ARG seconds (default 3)
  };
  Kind kind = Kind::kGarbage;
  std::string name;       // the kind as written: "garbage", "bad-checksum", ...
  double at_s = 0.0;      // seconds after the emulator started
  double argument = 0.0;  // bytes, packets or seconds; the kind's default when none was given
};

// The kinds, as written on the command line, in the order of the enum.
const std::vector<std::string>& RplidarEmulatorFaultNames();

// Parses "KIND@SECONDS[:ARG]". Throws std::invalid_argument, one line quoting `text`, on an
// unknown kind, a bad time or an argument that is not a number from 0 to 1e6.
RplidarEmulatorFault ParseRplidarEmulatorFault(const std::string& text);

// The faults' times, in order, for a FaultSchedule.
std::vector<double> FaultTimes(const std::vector<RplidarEmulatorFault>& faults);

}  // namespace rplidar
}  // namespace slammtt
