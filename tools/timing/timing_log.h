// The STAGE_TIMING messages of a log as TimingRecords (timing_table.h), for slammtt-timing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/log_reader.h"
#include "tools/timing/timing_table.h"

namespace slammtt {

inline constexpr int64_t kMaxPlausibleDurationNs = int64_t{3600} * 1000000000;

struct TimingLog {
  std::vector<TimingRecord> records;  // in log order
  int64_t undecodable = 0;            // not a stage_timing_t (slammtt::Decode refused it)
  int64_t negative = 0;               // a negative total or sub-stage duration: skipped
  // A total or sub-stage duration beyond an hour (kMaxPlausibleDurationNs): no stage works on
  // one message that long; such values are broken messages (INT64_MAX made the load negative).
  int64_t implausible = 0;
  LogReadResult read;                 // damage report of the log itself
};

// Reads every message on `channel`. Throws std::runtime_error when the file cannot be opened;
// a damaged log gives what was readable, with read.problem saying what happened.
TimingLog ReadTimingLog(const std::string& path, const std::string& channel);

}  // namespace slammtt
