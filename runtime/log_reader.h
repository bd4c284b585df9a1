// The one reader of LCM event logs: the events one by one through LCM's own reader
// (lcm::LogFile, as lcm-logplayer plays them), with the structural scan (log_scan.h) that says
// whether the log was damaged and where. Every program and test reads logs through here:
// slammtt-replay, slammtt-timing, slammtt-eval, the log source of LogBus (log_bus.h).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/log_scan.h"

namespace slammtt {

// One event of a log, owning its bytes.
struct LogEvent {
  int64_t eventnum = 0;
  int64_t timestamp_us = 0;
  std::string channel;
  std::vector<uint8_t> data;
};

// One event as the reader hands it over; `channel` and `data` are valid until the next read.
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

// Reads a log in file order. A truncated or corrupt end ends the events; result() says why.
class LogReader {
 public:
  // Scans and opens `path`. Throws std::runtime_error naming the path when it cannot be opened
  // or is not a regular file.
  explicit LogReader(const std::string& path);
  // The same with the scan already made (a caller that needs the channels before the first
  // event, as replay does). `scan` must be ScanLogFile(path).
  LogReader(const std::string& path, LogScan scan);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  // The next event (a copy), or nullopt at the end of what can be read.
  std::optional<LogEvent> Next();
  // The next event without a copy, valid until the next call; nullopt at the end.
  std::optional<LogEventView> NextView();

  const LogScan& scan() const { return scan_; }
  // What was read and, once the end is reached, why it ended early (if it did).
  LogReadResult result() const;

 private:
  std::string path_;
  LogScan scan_;
  std::unique_ptr<lcm::LogFile> file_;
  std::string channel_;  // of the last view
  int64_t events_read_ = 0;
};

// Calls `on_event` for every readable event in file order. Throws std::runtime_error when the
// file cannot be opened; exceptions from `on_event` propagate.
LogReadResult ForEachLogEvent(const std::string& path,
                              const std::function<void(const LogEventView&)>& on_event);

// The same with the structural scan already made. `scan` must be ScanLogFile(path).
LogReadResult ForEachLogEvent(const std::string& path, const LogScan& scan,
                              const std::function<void(const LogEventView&)>& on_event);

}  // namespace slammtt
