#include "drivers/rplidar/rplidar_emulator_faults.h"

#include "drivers/common/fault_schedule.h"

namespace slammtt {
namespace rplidar {
namespace {

using Kind = RplidarEmulatorFault::Kind;

// Bytes of garbage, packets corrupted or cut, seconds of silence or of a pulled cable.
double DefaultArgument(Kind kind) {
  switch (kind) {
    case Kind::kGarbage: return 100.0;
    case Kind::kSilence:
    case Kind::kMute:
    case Kind::kDisconnect: return 3.0;
    case Kind::kBadChecksum:
    case Kind::kDrop: return 1.0;
  }
  return 1.0;
}

}  // namespace

const std::vector<std::string>& RplidarEmulatorFaultNames() {
  static const std::vector<std::string> names = {"garbage", "bad-checksum", "drop",
                                                 "silence", "mute",         "disconnect"};
  return names;
}

RplidarEmulatorFault ParseRplidarEmulatorFault(const std::string& text) {
  const std::vector<std::string>& names = RplidarEmulatorFaultNames();
  const ScheduledFault scheduled = ParseScheduledFault(text, names);
  RplidarEmulatorFault fault;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == scheduled.kind) fault.kind = static_cast<Kind>(i);
  }
  fault.name = scheduled.kind;
  fault.at_s = scheduled.at_s;
  fault.argument = FaultNumber(scheduled.argument, DefaultArgument(fault.kind), text);
  return fault;
}

std::vector<double> FaultTimes(const std::vector<RplidarEmulatorFault>& faults) {
  std::vector<double> times;
  times.reserve(faults.size());
  for (const RplidarEmulatorFault& fault : faults) times.push_back(fault.at_s);
  return times;
}

}  // namespace rplidar
}  // namespace slammtt
