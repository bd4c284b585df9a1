#include "drivers/common/runtime_driver_log.h"

#include "runtime/log.h"

namespace slammtt {

void RuntimeDriverLog::Write(DriverLogLevel level, const std::string& line) {
  switch (level) {
    case DriverLogLevel::kDebug: LogLine(LogLevel::kDebug, line); return;
    case DriverLogLevel::kInfo: LogLine(LogLevel::kInfo, line); return;
    case DriverLogLevel::kWarning: LogLine(LogLevel::kWarning, line); return;
    case DriverLogLevel::kError: LogLine(LogLevel::kError, line); return;
  }
}

}  // namespace slammtt
