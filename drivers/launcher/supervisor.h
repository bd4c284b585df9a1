// Carries out a LaunchPlan: starts every process, prefixes their output lines with their names,
// restarts the ones that die (RestartPolicy), and stops them all on SIGINT/SIGTERM: SIGTERM to
// each process group, a grace period, then SIGKILL; processes marked stop_last (the logger) go
// after all the others, half a second after the last of them ended, so they record the others'
// last words.
//
// Each child runs in a process group of its own (a Ctrl-C in the terminal reaches only the
// launcher, which then stops the children in order) and gets SIGTERM should the launcher die
// (PR_SET_PDEATHSIG). Its stdin is /dev/null; its stdout and stderr lines go, prefixed, to the
// launcher's stdout and stderr.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "drivers/launcher/launch_plan.h"

namespace slammtt {

struct SupervisorSettings {
  std::string config_path;     // absolute: {config} and --config of the children
  std::string lcm_url;         // {lcm_url}
  // Given on the launcher's command line: also passed as --lcm-url to every pass_config process,
  // so that one option moves the whole stack to another bus.
  bool lcm_url_from_command_line = false;
  std::string self_directory;  // where slammtt-launch is: programs are looked up there first
};

// The executable a program name stands for: a name containing '/' is taken as it is (relative
// to the working directory); a bare name is looked up next to slammtt-launch, then in $PATH.
// std::runtime_error, one line naming where it looked, when there is none.
std::string ResolveProgram(const std::string& program, const std::string& self_directory);

// The directory slammtt-launch runs from (/proc/self/exe).
std::string SelfDirectory();

class Supervisor {
 public:
  // Resolves every program; std::runtime_error naming the process when one is missing.
  Supervisor(const LaunchPlan& plan, const SupervisorSettings& settings);
  ~Supervisor();
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // The command lines that Run() would start first, for --dry-run and the docs.
  std::vector<std::vector<std::string>> CommandLines() const;

  // Checks the bus against robot.network (bus_network.h) and creates the log directory
  // (std::runtime_error when either fails, before anything starts; a log directory other users
  // may write to without the sticky bit is refused), then
  // runs the stack until shutdown is requested (runtime/shutdown.h), until a process is given up
  // with on_give_up: stop_all, or until every process ended for good. Stops everything before
  // returning. Returns 0, or 1 when a process failed for good.
  int Run();

 private:
  struct Child;
  void Start(Child* child);
  void Pump(int timeout_ms);
  void Reap(bool stopping);
  void StopGroup(bool stop_last_group);
  // Between the two groups: time for the stop_last processes to take the others' last messages.
  void SettleBeforeTheLastGroup();
  static constexpr double kLastWordsSettleS = 0.5;
  void DrainAndClose(Child* child);
  // A new timestamped name in the log directory; with `create`, the file is created there
  // exclusively (never through a link, never over a file), so whoever opens it next (lcm-logger)
  // writes into the file the launcher made.
  std::string NextLogFile(bool create) const;
  std::vector<std::string> Arguments(const Child& child,
                                     const std::map<std::string, std::string>& variables) const;

  LaunchPlan plan_;
  SupervisorSettings settings_;
  std::vector<std::unique_ptr<Child>> children_;
  bool failed_ = false;
  bool stop_requested_by_failure_ = false;
};

}  // namespace slammtt
