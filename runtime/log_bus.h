// The Bus (bus.h) on log files (Drake's DrakeLcmLog idea): the events of an input log are the
// messages that arrive, and what is published goes into an output log. A stage or a process
// loop written against Bus runs unchanged on a recording, deterministically.
//
// Input: each Handle() delivers the next event of the log (LogReader, log_reader.h: file order,
// a damaged end ends the events; input_result() says why), so that a loop can run the timers
// that are due in message time between two events (log_time_us(): the timestamp of the event
// delivered last, a clock that never reads the wall).
// Output: a LogWriter (lcm_io.h): an event per publish, stamped with the timestamp of the input
// event being handled, or with the one given to SetTimestamp() since; the log appears only when
// Commit() succeeds.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "runtime/bus.h"
#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"

namespace slammtt {

class LogBus : public Bus {
 public:
  // Either path may be empty (no input: nothing arrives; no output: a publish throws
  // std::logic_error). Throws std::runtime_error naming the file when one cannot be opened or
  // created.
  LogBus(const std::string& input_path, const std::string& output_path);
  ~LogBus() override;

  void Publish(const std::string& channel, const void* data, int size) override;
  bool HasWaiting() const override { return next_.has_value(); }

  // True when every readable input event was delivered (at once without an input).
  bool InputDone() const { return !next_.has_value(); }
  // The timestamp of the input event delivered last (0 before the first).
  int64_t log_time_us() const { return log_time_us_; }
  // Stamps the following publishes (until the next input event is delivered).
  void SetTimestamp(int64_t timestamp_us) { output_timestamp_us_ = timestamp_us; }
  // The output log goes into place (LogWriter::Commit). Throws on an I/O error.
  void Commit();
  // What was read of the input and why it ended (LogReader::result()).
  LogReadResult input_result() const;
  int64_t events_written() const { return output_ ? output_->events_written() : 0; }

 protected:
  void StartReceiving(const std::string& /*channel*/) override {}
  int DeliverWaiting() override;

 private:
  std::unique_ptr<LogReader> input_;
  std::unique_ptr<LogWriter> output_;
  std::optional<LogEvent> next_;  // read ahead, so that HasWaiting() knows
  int64_t log_time_us_ = 0;
  int64_t output_timestamp_us_ = 0;
};

}  // namespace slammtt
