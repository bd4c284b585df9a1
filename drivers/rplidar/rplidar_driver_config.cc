#include "drivers/rplidar/rplidar_driver_config.h"

#include <stdexcept>
#include <string>

#include "drivers/common/byte_stream.h"
#include "runtime/command_line_options.h"
#include "runtime/config_options.h"

namespace slammtt {
namespace rplidar {
namespace {

// The keys the command line may set under their own name (--port, --baud).
const CommandLineOptions& RplidarCommandLineOptions() {
  static const CommandLineOptions options({"port", "baud"}, "rplidar");
  return options;
}

}  // namespace

RplidarDriverOptions ReadRplidarDriverOptions(const Config& section) {
  RplidarDriverOptions options;
  ConfigOptionReader reader(section);
  VisitRplidarDriverOptions(&reader, &options);
  section.CheckUnused();
  const std::string problem = CheckRplidarSessionOptions(options);
  if (!problem.empty()) FailOptionsProblem(section, problem);
  return options;
}

void AddRplidarDriverOptions(CommandLine* command_line) {
  RplidarCommandLineOptions().Declare(command_line, VisitRplidarDriverOptions);
  command_line->AddOption("mode", "MODE",
                          "scan mode: standard or express (rplidar.scan_mode, default express)");
  command_line->AddFlag("options-table",
                        "print the table of every key of the rplidar: section (Markdown, "
                        "docs/rplidar.md) and exit");
}

void ApplyRplidarDriverCommandLine(const CommandLine& command_line,
                                   RplidarDriverOptions* options) {
  RplidarCommandLineOptions().Apply(command_line, VisitRplidarDriverOptions, options);
  if (auto mode = command_line.Value("mode")) {
    try {
      options->scan_mode = ParseScanMode(*mode);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--mode: ") + e.what());
    }
  }
}

void CheckRplidarDriverOptions(const RplidarDriverOptions& options) {
  CheckEndpoint(options.port, options.baud);
  const std::string problem = CheckRplidarSessionOptions(options);
  if (!problem.empty()) throw std::invalid_argument(problem);
}

}  // namespace rplidar
}  // namespace slammtt
