// One logging style for every process of the stack: one line per event on stderr,
//   slammtt-world: warning: scenario has no static object
// The program name is set once by ProcessMain (process.h). Lines from several threads never
// interleave. Logging is for people: nothing a stage computes depends on it.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>

#include "common/report_count.h"

namespace slammtt {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarning = 2, kError = 3 };

// Name printed in front of every line (default "slammtt").
void SetLogProgramName(const std::string& name);
// Lines below this level are not printed (default kInfo).
void SetLogLevel(LogLevel level);
LogLevel GetLogLevel();

// Writes one line "<program>: <level>: <message>" to stderr. Newlines inside the message are
// replaced by spaces so that every event stays one line.
void LogLine(LogLevel level, const std::string& message);

// Stream-style front end: Log(LogLevel::kInfo) << "read " << n << " beams";
class Log {
 public:
  explicit Log(LogLevel level) : level_(level) {}
  ~Log() { LogLine(level_, stream_.str()); }
  Log(const Log&) = delete;
  Log& operator=(const Log&) = delete;

  template <class T>
  Log& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }

 private:
  LogLevel level_;
  std::ostringstream stream_;
};

// IsReportable(count), how often a repeated problem is reported: common/report_count.h.

inline Log LogDebug() { return Log(LogLevel::kDebug); }
inline Log LogInfo() { return Log(LogLevel::kInfo); }
inline Log LogWarning() { return Log(LogLevel::kWarning); }
inline Log LogError() { return Log(LogLevel::kError); }

}  // namespace slammtt
