#include "runtime/log_bus.h"

#include <stdexcept>
#include <utility>

namespace slammtt {

LogBus::LogBus(const std::string& input_path, const std::string& output_path) {
  if (!input_path.empty()) {
    input_ = std::make_unique<LogReader>(input_path);
    next_ = input_->Next();
  }
  if (!output_path.empty()) output_ = std::make_unique<LogWriter>(output_path);
}

LogBus::~LogBus() = default;  // an uncommitted output log removes itself

void LogBus::Publish(const std::string& channel, const void* data, int size) {
  if (!output_) throw std::logic_error("LogBus: publish on " + channel + " without an output log");
  output_->Write(output_timestamp_us_, channel, data, size);
}

void LogBus::Commit() {
  if (output_) output_->Commit();
}

LogReadResult LogBus::input_result() const {
  return input_ ? input_->result() : LogReadResult{};
}

int LogBus::DeliverWaiting() {
  if (!next_) return 0;
  const LogEvent event = std::move(*next_);
  next_ = input_->Next();
  log_time_us_ = event.timestamp_us;
  output_timestamp_us_ = event.timestamp_us;
  Dispatch(event.channel, event.data.data(), static_cast<int>(event.data.size()));
  return 1;
}

}  // namespace slammtt
