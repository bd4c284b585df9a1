// What slammtt-launch starts: the `robot:` section of the robot's stack configuration, read into
// a plan. Pure (no processes, no files): the supervisor (supervisor.h) carries it out.
//
//   robot:
//     network: loopback                  # or lan: who may reach the bus (bus_network.h)
//     log_directory: /var/log/slammtt   # {log_file} = <dir>/slammtt-YYYYmmdd-HHMMSS.lcm
//     stop_grace_s: 5.0                  # SIGTERM, then SIGKILL after this long
//     max_restarts: 5                    # restarts in a row before giving up on a process
//     restart_initial_s: 1.0             # backoff: 1, 2, 4, ... s, at most restart_max_s
//     restart_max_s: 30.0
//     restart_reset_after_s: 60.0        # a run this long forgets the earlier failures
//     on_give_up: stop_all               # or keep_running
//     processes:
//       - name: logger
//         program: lcm-logger                # --force: the launcher created {log_file} itself
//         args: ["--quiet", "--force", "--lcm-url={lcm_url}", "{log_file}"]
//         pass_config: false
//         stop_last: true
//       - name: p3dx
//         program: slammtt-p3dx            # gets --config <this file> before its args
//
// Arguments may use {config} (the configuration file, absolute), {lcm_url} (the bus of the
// `lcm:` section or the default), {log_directory} and {log_file} (a new timestamped name at
// every start of the process). Unknown keys and unknown {names} are configuration errors.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/options_schema.h"
#include "runtime/config.h"

namespace slammtt {

enum class RestartMode {
  kOnFailure,  // restart after a non-zero exit or a signal (default)
  kAlways,     // restart after any exit
  kNever,
};

struct ProcessSpec {
  std::string name;                // [A-Za-z0-9_-]+, unique; the prefix of its output lines
  std::string program;             // as configured: a path, or a name looked up (see supervisor.h)
  std::vector<std::string> args;   // unexpanded
  bool pass_config = true;         // "--config FILE" before args
  bool stop_last = false;          // stopped after every other process (the logger)
  RestartMode restart = RestartMode::kOnFailure;
};

enum class GiveUpAction {
  kStopAll,      // stop the whole stack and exit 1 (default: a robot without a driver is blind)
  kKeepRunning,  // leave the others running; exit 1 at the end
};

// Which machines the stack's bus is for (docs/robot.md, "Who can drive the robot").
enum class BusNetwork {
  kLoopback,  // this computer only (default): the bus must keep to the loopback interface
  kLan,       // base stations on a LAN too: commands must then be signed (p3dx.command_key_file)
};

struct LaunchPlan {
  std::vector<ProcessSpec> processes;  // in start order
  BusNetwork network = BusNetwork::kLoopback;
  std::string log_directory = "logs";
  double stop_grace_s = 5.0;
  int max_restarts = 5;
  double restart_initial_s = 1.0;
  double restart_max_s = 30.0;
  double restart_reset_after_s = 60.0;
  GiveUpAction on_give_up = GiveUpAction::kStopAll;
};

// The options schemas of the `robot:` section's settings (every key but `processes`) and of an
// entry of `processes` (pass_config, stop_last, restart; name, program and args are its format).
// Keys are the field names. The reader, CheckLaunchPlan and the tables of docs/robot.md
// (slammtt-launch --options-table) come from them.
void VisitLaunchPlanSettings(OptionVisitor* visitor, LaunchPlan* plan);
void VisitProcessSettings(OptionVisitor* visitor, ProcessSpec* process);

// Empty when the supervisor can carry the plan out; otherwise one line naming the first bad
// setting by its key ("stop_grace_s = 0: must be in (0, 86400]", "processes[1].restart ..."):
// the schemas' ranges, a non-empty log_directory, restart_max_s >= restart_initial_s, and for
// every process a name of 1-32 of [A-Za-z0-9_-] used once and a program.
std::string CheckLaunchPlan(const LaunchPlan& plan);

// The Markdown tables of the settings of `robot:` and of an entry of `processes`, each under a
// line naming it (docs/robot.md, "slammtt-launch").
std::string LaunchPlanOptionsTables();

// Reads and checks the `robot:` section (ConfigError naming file, line and key). Runs
// CheckUnused() on it.
LaunchPlan ReadLaunchPlan(const Config& robot_section);

// Replaces {config}, {lcm_url}, {log_directory}, {log_file} in `text`; std::invalid_argument
// naming the first unknown or unterminated {...}. "{{" and "}}" stand for literal braces.
std::string ExpandLaunchArgument(const std::string& text,
                                 const std::map<std::string, std::string>& variables);

// The full argument vector (without the program) of one start of `spec`.
std::vector<std::string> LaunchArguments(const ProcessSpec& spec, const std::string& config_path,
                                         const std::map<std::string, std::string>& variables);

// "slammtt-20250131-142501.lcm" for a broken-down local time (year, month 1-12, day, hour,
// minute, second).
std::string LogFileName(int year, int month, int day, int hour, int minute, int second);

}  // namespace slammtt
