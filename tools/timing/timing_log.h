// The STAGE_TIMING messages of a log as TimingRecords (timing_table.h), for slammtt-timing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/replay/log_events.h"
#include "tools/timing/timing_table.h"

namespace slammtt {

struct TimingLog {
  std::vector<TimingRecord> records;  // in log order
  int64_t undecodable = 0;            // not a stage_timing_t (slammtt::Decode refused it)
  int64_t negative = 0;               // a negative total or sub-stage duration: skipped
  LogReadResult read;                 // damage report of the log itself
};

// Reads every message on `channel`. Throws std::runtime_error when the file cannot be opened;
// a damaged log gives what was readable, with read.problem saying what happened.
TimingLog ReadTimingLog(const std::string& path, const std::string& channel);

}  // namespace slammtt
