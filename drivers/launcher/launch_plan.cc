#include "drivers/launcher/launch_plan.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "runtime/config_options.h"

namespace slammtt {
namespace {

const std::set<std::string>& KnownVariables() {
  static const std::set<std::string> names = {"config", "lcm_url", "log_directory", "log_file"};
  return names;
}

bool ValidName(const std::string& name) {
  if (name.empty() || name.size() > 32) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

void VisitLaunchPlanSettings(OptionVisitor* v, LaunchPlan* plan) {
  using R = OptionRange;
  // A day at most: the supervisor turns these into millisecond poll timeouts (int).
  const R seconds = R::AboveUpTo(0, 86400);
  int network = static_cast<int>(plan->network);
  v->Choice("network", &network, {"loopback", "lan"},
            "`loopback`: the bus must keep to this computer (`lcm.url` memq or udpm with ttl=0, "
            "the group routed on lo), else the launcher refuses to start; `lan`: base stations "
            "on a LAN reach it (\"Who can drive the robot\")");
  plan->network = static_cast<BusNetwork>(network);
  v->String("log_directory", &plan->log_directory,
            "not empty; created if missing; refused if other users may write to it without the "
            "sticky bit; `{log_file}` is a new file in it (below)");
  v->Double("stop_grace_s", &plan->stop_grace_s, seconds,
            "after SIGTERM, SIGKILL for what still runs");
  v->Int("max_restarts", &plan->max_restarts, R::Between(0, 1000),
         "restarts in a row before a process is given up");
  v->Double("restart_initial_s", &plan->restart_initial_s, seconds,
            "restart backoff: the first delay, doubling ...");
  v->Double("restart_max_s", &plan->restart_max_s, seconds, "... up to this");
  v->Double("restart_reset_after_s", &plan->restart_reset_after_s, seconds,
            "a run this long forgets the failures before it");
  int on_give_up = static_cast<int>(plan->on_give_up);
  v->Choice("on_give_up", &on_give_up, {"stop_all", "keep_running"},
            "`stop_all`: stop the stack and exit 1 (systemd then restarts it); `keep_running`: "
            "the others go on, exit 1 at the end");
  plan->on_give_up = static_cast<GiveUpAction>(on_give_up);
}

void VisitProcessSettings(OptionVisitor* v, ProcessSpec* process) {
  v->Bool("pass_config", &process->pass_config, "put `--config FILE` before the arguments");
  v->Bool("stop_last", &process->stop_last,
          "stopped after every other process (the logger, so it records the others' last "
          "status)");
  int restart = static_cast<int>(process->restart);
  v->Choice("restart", &restart, {"on_failure", "always", "never"},
            "`on_failure` (non-zero exit or signal), `always`, `never`");
  process->restart = static_cast<RestartMode>(restart);
}

std::string CheckLaunchPlan(const LaunchPlan& plan) {
  LaunchPlan copy = plan;
  OptionRangeCheck check;
  VisitLaunchPlanSettings(&check, &copy);
  if (!check.problem().empty()) return check.problem();
  if (plan.log_directory.empty()) return "log_directory must not be empty";
  if (plan.restart_max_s < plan.restart_initial_s) {
    return "restart_max_s must not be less than restart_initial_s";
  }
  std::set<std::string> names;
  for (size_t i = 0; i < copy.processes.size(); ++i) {
    ProcessSpec& spec = copy.processes[i];
    const std::string where = "processes[" + std::to_string(i) + "].";
    OptionRangeCheck process_check;
    VisitProcessSettings(&process_check, &spec);
    if (!process_check.problem().empty()) return where + process_check.problem();
    if (!ValidName(spec.name)) {
      return where + "name '" + spec.name + "' is not 1-32 of [A-Za-z0-9_-]";
    }
    if (!names.insert(spec.name).second) return where + "name '" + spec.name + "' is used twice";
    if (spec.program.empty()) return where + "program must not be empty";
  }
  return "";
}

std::string LaunchPlanOptionsTables() {
  LaunchPlan plan;
  OptionsMarkdownTable settings;
  VisitLaunchPlanSettings(&settings, &plan);
  ProcessSpec process;
  OptionsMarkdownTable process_settings;
  VisitProcessSettings(&process_settings, &process);
  return "`robot:`\n\n" + settings.Table() + "\nEach entry of `processes`:\n\n" +
         process_settings.Table();
}

LaunchPlan ReadLaunchPlan(const Config& robot) {
  LaunchPlan plan;
  ConfigOptionReader reader(robot);
  VisitLaunchPlanSettings(&reader, &plan);
  if (plan.log_directory.empty()) robot.FailKey("log_directory", "must not be empty");
  if (plan.restart_max_s < plan.restart_initial_s) {
    robot.FailKey("restart_max_s", "must not be less than restart_initial_s");
  }

  if (!robot.Has("processes")) robot.Fail("missing key 'processes' (the programs to start)");
  const std::vector<Config> items = robot.Items("processes");
  if (items.empty()) robot.FailKey("processes", "lists no process");
  std::set<std::string> names;
  for (const Config& item : items) {
    if (!item.IsMap()) item.Fail("expected a mapping with name and program");
    ProcessSpec spec;
    spec.name = item.RequireString("name");
    if (!ValidName(spec.name)) {
      item.FailKey("name", "'" + spec.name + "' is not 1-32 of [A-Za-z0-9_-]");
    }
    if (!names.insert(spec.name).second) item.FailKey("name", "'" + spec.name + "' is used twice");
    spec.program = item.RequireString("program");
    if (spec.program.empty()) item.FailKey("program", "must not be empty");
    for (const Config& arg : item.Items("args")) {
      if (!arg.IsScalar()) arg.Fail("an argument must be a string");
      spec.args.push_back(arg.AsString());
      try {
        ExpandLaunchArgument(spec.args.back(), {{"config", ""}, {"lcm_url", ""},
                                                {"log_directory", ""}, {"log_file", ""}});
      } catch (const std::invalid_argument& e) {
        arg.Fail(e.what());
      }
    }
    ConfigOptionReader process_reader(item);
    VisitProcessSettings(&process_reader, &spec);
    plan.processes.push_back(std::move(spec));
  }
  robot.CheckUnused();
  const std::string problem = CheckLaunchPlan(plan);
  if (!problem.empty()) robot.Fail(problem);  // (every condition was reported at its line)
  return plan;
}

std::string ExpandLaunchArgument(const std::string& text,
                                 const std::map<std::string, std::string>& variables) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '{' && i + 1 < text.size() && text[i + 1] == '{') {
      out.push_back('{');
      ++i;
    } else if (c == '}' && i + 1 < text.size() && text[i + 1] == '}') {
      out.push_back('}');
      ++i;
    } else if (c == '{') {
      const size_t close = text.find('}', i);
      if (close == std::string::npos) {
        throw std::invalid_argument("unterminated '{' in argument '" + text + "'");
      }
      const std::string name = text.substr(i + 1, close - i - 1);
      const auto found = variables.find(name);
      if (KnownVariables().count(name) == 0 || found == variables.end()) {
        throw std::invalid_argument("unknown {" + name + "} in argument '" + text +
                                    "' (known: {config}, {lcm_url}, {log_directory}, {log_file})");
      }
      out += found->second;
      i = close;
    } else if (c == '}') {
      throw std::invalid_argument("unmatched '}' in argument '" + text + "' (write }} for a brace)");
    } else {
      out.push_back(c);
    }
  }
  return out;
}

std::vector<std::string> LaunchArguments(const ProcessSpec& spec, const std::string& config_path,
                                         const std::map<std::string, std::string>& variables) {
  std::vector<std::string> args;
  if (spec.pass_config) {
    args.push_back("--config");
    args.push_back(config_path);
  }
  for (const std::string& arg : spec.args) args.push_back(ExpandLaunchArgument(arg, variables));
  return args;
}

std::string LogFileName(int year, int month, int day, int hour, int minute, int second) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "slammtt-%04d%02d%02d-%02d%02d%02d.lcm", year, month, day,
                hour, minute, second);
  return buffer;
}

}  // namespace slammtt
