#include "drivers/p3dx/p3dx_driver_config.h"

#include <stdexcept>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/p3dx/p3dx_odometry.h"
#include "runtime/command_line_options.h"
#include "runtime/config_options.h"
#include "runtime/lcm_url.h"

namespace slammtt {

P3dxDriverOptions ReadP3dxDriverOptions(const Config& section) {
  P3dxDriverOptions o;
  ConfigOptionReader reader(section);
  VisitP3dxDriverOptions(&reader, &o);
  section.CheckUnused();
  const std::string problem = CheckP3dxDriverOptions(o);
  if (!problem.empty()) FailOptionsProblem(section, problem);
  try {
    CheckEndpoint(o.port, o.baud);
  } catch (const std::invalid_argument& e) {
    section.FailKey("port", e.what());
  }
  return o;
}

namespace {

// The keys the command line may set too (runtime/command_line_options.h): --port, --baud, ...
const CommandLineOptions& P3dxCommandLineOptions() {
  static const CommandLineOptions options(
      {"port", "baud", "max_linear_mps", "max_angular_radps", "command_timeout_s"}, "p3dx");
  return options;
}

}  // namespace

void AddP3dxDriverOptions(CommandLine* command_line) {
  P3dxCommandLineOptions().Declare(command_line, VisitP3dxDriverOptions);
  command_line->AddFlag("options-table",
                        "print the table of every key of the p3dx: section (Markdown, "
                        "docs/p3dx.md) and exit");
}

void ApplyP3dxDriverCommandLine(const CommandLine& command_line, P3dxDriverOptions* options) {
  P3dxCommandLineOptions().Apply(command_line, VisitP3dxDriverOptions, options);
  try {
    ValidateP3dxDriverOptions(*options);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

void CheckCommandAuthenticationForBus(const P3dxDriverOptions& options,
                                      const std::string& lcm_url) {
  if (options.command_authentication != P3dxDriverOptions::CommandAuthentication::kNone) return;
  if (!IsLocalOnly(ParseLcmUrl(lcm_url))) {
    throw std::invalid_argument(
        "p3dx.command_authentication: none is for a bus whose packets stay on this computer "
        "(udpm://...?ttl=0), not '" +
        lcm_url + "': give the robot a command key instead (docs/robot.md)");
  }
  if (!options.command_key_file.empty()) {
    throw std::invalid_argument(
        "p3dx.command_authentication: none and p3dx.command_key_file exclude each other");
  }
}

void ValidateP3dxDriverOptions(const P3dxDriverOptions& o) {
  CheckEndpoint(o.port, o.baud);
  const std::string problem = CheckP3dxDriverOptions(o);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace slammtt
