// The programs' DriverLog: a device session's lines go to the process log (runtime/log.h), at
// their level, as "<program>: <level>: <line>".
#pragma once

#include <string>

#include "drivers/common/driver_log.h"

namespace slammtt {

class RuntimeDriverLog : public DriverLog {
 public:
  void Write(DriverLogLevel level, const std::string& line) override;
};

}  // namespace slammtt
