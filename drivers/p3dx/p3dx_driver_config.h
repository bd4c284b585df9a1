// The P3-DX driver's options from the stack configuration (`p3dx:` section) and the command
// line (which wins), and their checks before the program opens anything (docs/p3dx.md).
#pragma once

#include <string>

#include "drivers/p3dx/p3dx_driver_options.h"
#include "runtime/command_line.h"
#include "runtime/config.h"

namespace slammtt {

// Reads the `p3dx:` section through the schema (VisitP3dxDriverOptions): absent keys keep the
// defaults; ConfigError naming file, line and key for an unknown key (CheckUnused), a value of
// the wrong type or out of range, a condition of CheckP3dxDriverOptions or a malformed port.
P3dxDriverOptions ReadP3dxDriverOptions(const Config& section);

// --port, --baud, --max-linear-mps, --max-angular-radps, --command-timeout-s, from the schema
// (runtime/command_line_options.h), and the flag --options-table (the program prints
// P3dxDriverOptionsTable() and exits). Apply: UsageError naming the option for a bad value.
void AddP3dxDriverOptions(CommandLine* command_line);
void ApplyP3dxDriverCommandLine(const CommandLine& command_line, P3dxDriverOptions* options);

// Throws std::invalid_argument, one line naming the option, when CheckP3dxDriverOptions finds a
// problem or the port is not a well-formed endpoint (drivers/common CheckEndpoint).
void ValidateP3dxDriverOptions(const P3dxDriverOptions& options);

// Throws std::invalid_argument, one line, when commands are unauthenticated (kNone) on a bus
// whose packets may leave the host: anything but memq or udpm with ttl=0 (runtime/lcm_url.h).
void CheckCommandAuthenticationForBus(const P3dxDriverOptions& options,
                                      const std::string& lcm_url);

}  // namespace slammtt
