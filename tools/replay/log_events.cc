#include "tools/replay/log_events.h"

#include <lcm/lcm-cpp.hpp>

#include <stdexcept>

namespace slammtt {

LogReadResult ForEachLogEvent(const std::string& path,
                              const std::function<void(const LogEventView&)>& on_event) {
  return ForEachLogEvent(path, ScanLogFile(path), on_event);
}

LogReadResult ForEachLogEvent(const std::string& path, const LogScan& scan,
                              const std::function<void(const LogEventView&)>& on_event) {
  LogReadResult result;
  result.scan = scan;
  lcm::LogFile file(path, "r");
  if (!file.good()) throw std::runtime_error(path + ": cannot open log file");
  while (const lcm::LogEvent* raw = file.readNextEvent()) {
    ++result.events_read;
    on_event(LogEventView{raw->eventnum, raw->timestamp, raw->channel, raw->data, raw->datalen});
  }
  if (result.scan.damage == LogDamage::kCorrupt) {
    result.corrupt = true;
    result.problem = path + ": " + result.scan.damage_description + "; read the " +
                     std::to_string(result.events_read) + " events before it";
  } else if (result.events_read != result.scan.complete_events) {
    result.corrupt = true;
    result.problem = path + ": LCM read " + std::to_string(result.events_read) + " of " +
                     std::to_string(result.scan.complete_events) + " complete events";
  } else if (result.scan.damage == LogDamage::kTruncatedTail) {
    result.problem = path + ": " + result.scan.damage_description;
  }
  return result;
}

}  // namespace slammtt
