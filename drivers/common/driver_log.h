// What a device session tells the people running it: one line per event (opened a link, lost
// it, refused a command), at a level. The sessions are pure (no runtime/, no message), so they
// write to this interface and the program's adapter hands the lines to the process log
// (RuntimeDriverLog, runtime_driver_log.h); a test records them. Nothing a session computes
// depends on it.
#pragma once

#include <sstream>
#include <string>

namespace slammtt {

enum class DriverLogLevel { kDebug, kInfo, kWarning, kError };

class DriverLog {
 public:
  virtual ~DriverLog() = default;
  // One event, one line, without the program name or the level (the adapter adds them).
  virtual void Write(DriverLogLevel level, const std::string& line) = 0;
};

// Stream front end: DriverLogLine(log, DriverLogLevel::kInfo) << "opened " << endpoint;
// writes the line when it goes out of scope. `log` may be null: the line is dropped.
class DriverLogLine {
 public:
  DriverLogLine(DriverLog* log, DriverLogLevel level) : log_(log), level_(level) {}
  ~DriverLogLine() {
    if (log_ != nullptr) log_->Write(level_, stream_.str());
  }
  DriverLogLine(const DriverLogLine&) = delete;
  DriverLogLine& operator=(const DriverLogLine&) = delete;

  template <class T>
  DriverLogLine& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }
  // std::hex and friends.
  DriverLogLine& operator<<(std::ios_base& (*manipulator)(std::ios_base&)) {
    stream_ << manipulator;
    return *this;
  }

 private:
  DriverLog* log_;
  DriverLogLevel level_;
  std::ostringstream stream_;
};

}  // namespace slammtt
