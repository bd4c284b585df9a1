// The RPLIDAR driver's options from the stack configuration (`rplidar:` section; docs/rplidar.md)
// and the command line (which wins), and their checks before the program opens anything.
#pragma once

#include "drivers/rplidar/rplidar_driver_options.h"
#include "runtime/command_line.h"
#include "runtime/config.h"

namespace slammtt {
namespace rplidar {

// Reads the `rplidar:` section through the schema (VisitRplidarDriverOptions): absent keys keep
// the defaults; ConfigError naming file, line and key for an unknown key (CheckUnused), a value
// of the wrong type or out of range, or a condition of CheckRplidarSessionOptions.
RplidarDriverOptions ReadRplidarDriverOptions(const Config& section);

// --port and --baud from the schema (runtime/command_line_options.h), --mode (scan_mode:
// standard or express), and the flag --options-table (the program prints
// RplidarDriverOptionsTable() and exits). Apply: UsageError naming the option for a bad value.
void AddRplidarDriverOptions(CommandLine* command_line);
void ApplyRplidarDriverCommandLine(const CommandLine& command_line,
                                   RplidarDriverOptions* options);

// Throws std::invalid_argument with a one-line reason when CheckRplidarSessionOptions finds a
// problem or the port is not a well-formed endpoint (drivers/common CheckEndpoint).
void CheckRplidarDriverOptions(const RplidarDriverOptions& options);

}  // namespace rplidar
}  // namespace slammtt
