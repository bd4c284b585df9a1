#include "runtime/log_reader.h"

#include <stdexcept>
#include <utility>

namespace slammtt {

LogReader::LogReader(const std::string& path) : LogReader(path, ScanLogFile(path)) {}

LogReader::LogReader(const std::string& path, LogScan scan)
    : path_(path), scan_(std::move(scan)), file_(std::make_unique<lcm::LogFile>(path, "r")) {
  if (!file_->good()) throw std::runtime_error(path + ": cannot open log file");
}

LogReader::~LogReader() = default;

std::optional<LogEventView> LogReader::NextView() {
  const lcm::LogEvent* raw = file_->readNextEvent();
  if (raw == nullptr) return std::nullopt;
  ++events_read_;
  channel_ = raw->channel;
  return LogEventView{raw->eventnum, raw->timestamp, channel_, raw->data, raw->datalen};
}

std::optional<LogEvent> LogReader::Next() {
  const std::optional<LogEventView> view = NextView();
  if (!view) return std::nullopt;
  LogEvent event;
  event.eventnum = view->eventnum;
  event.timestamp_us = view->timestamp_us;
  event.channel = view->channel;
  const auto* bytes = static_cast<const uint8_t*>(view->data);
  event.data.assign(bytes, bytes + view->size);
  return event;
}

LogReadResult LogReader::result() const {
  LogReadResult result;
  result.scan = scan_;
  result.events_read = events_read_;
  if (scan_.damage == LogDamage::kCorrupt) {
    result.corrupt = true;
    result.problem = path_ + ": " + scan_.damage_description + "; read the " +
                     std::to_string(events_read_) + " events before it";
  } else if (events_read_ != scan_.complete_events) {
    result.corrupt = true;
    result.problem = path_ + ": LCM read " + std::to_string(events_read_) + " of " +
                     std::to_string(scan_.complete_events) + " complete events";
  } else if (scan_.damage == LogDamage::kTruncatedTail) {
    result.problem = path_ + ": " + scan_.damage_description;
  }
  return result;
}

LogReadResult ForEachLogEvent(const std::string& path,
                              const std::function<void(const LogEventView&)>& on_event) {
  return ForEachLogEvent(path, ScanLogFile(path), on_event);
}

LogReadResult ForEachLogEvent(const std::string& path, const LogScan& scan,
                              const std::function<void(const LogEventView&)>& on_event) {
  LogReader reader(path, scan);
  while (const std::optional<LogEventView> event = reader.NextView()) on_event(*event);
  return reader.result();
}

}  // namespace slammtt
