// The RPLIDAR driver's options from the stack configuration (`rplidar:` section; docs/rplidar.md)
// and their checks before the program opens anything.
#pragma once

#include "drivers/rplidar/rplidar_driver_options.h"
#include "runtime/config.h"

namespace slammtt {
namespace rplidar {

// Reads the `rplidar:` section; ConfigError naming file, line and key on a bad value. The
// caller calls CheckUnused() on the section afterwards.
RplidarDriverOptions ReadRplidarDriverOptions(const Config& section);
// Throws std::invalid_argument with a one-line reason when options contradict each other or the
// port is not a well-formed endpoint (drivers/common CheckEndpoint).
void CheckRplidarDriverOptions(const RplidarDriverOptions& options);

}  // namespace rplidar
}  // namespace slammtt
