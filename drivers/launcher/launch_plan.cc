#include "drivers/launcher/launch_plan.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

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

// A day at most: the supervisor turns these into millisecond poll timeouts (int).
double PositiveSeconds(const Config& section, const std::string& key, double fallback) {
  const double value = section.GetDouble(key, fallback);
  if (!(value > 0.0) || value > 86400.0) {
    section.FailKey(key, "must be a number of seconds in (0, 86400]");
  }
  return value;
}

}  // namespace

LaunchPlan ReadLaunchPlan(const Config& robot) {
  LaunchPlan plan;
  const std::string network = robot.GetString("network", "loopback");
  if (network == "loopback") {
    plan.network = BusNetwork::kLoopback;
  } else if (network == "lan") {
    plan.network = BusNetwork::kLan;
  } else {
    robot.FailKey("network", "expected loopback or lan, got '" + network + "'");
  }
  plan.log_directory = robot.GetString("log_directory", plan.log_directory);
  if (plan.log_directory.empty()) robot.FailKey("log_directory", "must not be empty");
  plan.stop_grace_s = PositiveSeconds(robot, "stop_grace_s", plan.stop_grace_s);
  const int64_t max_restarts = robot.GetInt("max_restarts", plan.max_restarts);
  if (max_restarts < 0 || max_restarts > 1000) robot.FailKey("max_restarts", "must be within 0..1000");
  plan.max_restarts = static_cast<int>(max_restarts);
  plan.restart_initial_s = PositiveSeconds(robot, "restart_initial_s", plan.restart_initial_s);
  plan.restart_max_s = PositiveSeconds(robot, "restart_max_s", plan.restart_max_s);
  if (plan.restart_max_s < plan.restart_initial_s) {
    robot.FailKey("restart_max_s", "must not be less than restart_initial_s");
  }
  plan.restart_reset_after_s =
      PositiveSeconds(robot, "restart_reset_after_s", plan.restart_reset_after_s);
  const std::string give_up = robot.GetString("on_give_up", "stop_all");
  if (give_up == "stop_all") {
    plan.on_give_up = GiveUpAction::kStopAll;
  } else if (give_up == "keep_running") {
    plan.on_give_up = GiveUpAction::kKeepRunning;
  } else {
    robot.FailKey("on_give_up", "expected stop_all or keep_running, got '" + give_up + "'");
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
    spec.pass_config = item.GetBool("pass_config", spec.pass_config);
    spec.stop_last = item.GetBool("stop_last", spec.stop_last);
    const std::string restart = item.GetString("restart", "on_failure");
    if (restart == "on_failure") {
      spec.restart = RestartMode::kOnFailure;
    } else if (restart == "always") {
      spec.restart = RestartMode::kAlways;
    } else if (restart == "never") {
      spec.restart = RestartMode::kNever;
    } else {
      item.FailKey("restart", "expected on_failure, always or never, got '" + restart + "'");
    }
    plan.processes.push_back(std::move(spec));
  }
  robot.CheckUnused();
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
