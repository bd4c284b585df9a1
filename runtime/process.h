// What every slammtt program shares: the standard options, the stack configuration, the bus
// URL and channel names, and the uniform handling of fatal errors.
//
//   int main(int argc, char** argv) {
//     return slammtt::ProcessMain(argc, argv, "slammtt-segmenter", [&](int c, char** v) {
//       slammtt::CommandLine cl("slammtt-segmenter", "[options]", "Splits scans into features.");
//       slammtt::AddStandardOptions(&cl);
//       if (!cl.Parse(c, v)) return 0;
//       slammtt::ProcessSettings settings = slammtt::LoadProcessSettings(cl);
//       ...
//     });
//   }
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "runtime/channels.h"
#include "runtime/command_line.h"
#include "runtime/config.h"

namespace slammtt {

// Top-level sections a stack configuration file may have; anything else is an error.
const std::vector<std::string>& KnownConfigSections();

// --config FILE, --lcm-url URL, --channel KEY=NAME, --verbose, --quiet.
void AddStandardOptions(CommandLine* command_line);

struct ProcessSettings {
  Config config;           // the whole stack file (an empty mapping without --config)
  std::string config_path; // empty without --config
  std::string lcm_url;     // resolved: option, lcm.url, LCM_DEFAULT_URL, default
  Channels channels;       // defaults, then channels:, then --channel
};

// Reads --config (if any), checks its top-level sections, resolves the URL and channels and
// applies --verbose/--quiet. The caller reads its own sections from settings.config and then
// calls CheckUnused() on each of them.
ProcessSettings LoadProcessSettings(const CommandLine& command_line);

// Runs `body` with the program's name in every log line, SIGINT/SIGTERM handlers installed and
// every error turned into one line on stderr and an exit status: 2 for a UsageError, 1 for any
// other error. `body` returns the exit status for a normal end (0 after a requested shutdown).
int ProcessMain(int argc, char** argv, const std::string& program,
                const std::function<int(int, char**)>& body);

}  // namespace slammtt
