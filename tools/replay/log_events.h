// Reads a log's events one by one through LCM's own reader (lcm::LogFile, as lcm-logplayer
// does), with the structural scan (log_scan.h) that says whether the log was damaged and where.
// Every tool reads logs through here: slammtt-replay, slammtt-timing and slammtt-eval.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "tools/replay/log_scan.h"

namespace slammtt {

// One event as the reader hands it over; `data` is valid during the callback only.
struct LogEventView {
  int64_t eventnum = 0;
  int64_t timestamp_us = 0;
  const std::string& channel;
  const void* data = nullptr;
  int size = 0;
};

struct LogReadResult {
  LogScan scan;
  int64_t events_read = 0;
  // One line when the log is damaged: "<path>: corrupt ...; read the N events before it" or
  // "<path>: truncated final event ..." (every complete event was read: a caller may go on).
  std::string problem;
  bool corrupt = false;  // damage other than a truncated final event
};

// Calls `on_event` for every readable event in file order. Throws std::runtime_error when the
// file cannot be opened; exceptions from `on_event` propagate.
LogReadResult ForEachLogEvent(const std::string& path,
                              const std::function<void(const LogEventView&)>& on_event);

// The same with the structural scan already made (a caller that needs the log's channels before
// the first event, as replay does). `scan` must be ScanLogFile(path).
LogReadResult ForEachLogEvent(const std::string& path, const LogScan& scan,
                              const std::function<void(const LogEventView&)>& on_event);

}  // namespace slammtt
