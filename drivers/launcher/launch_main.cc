// slammtt-launch: starts the robot's stack from one configuration file (see launch_plan.h,
// supervisor.h and docs/robot.md).
#include <limits.h>
#include <stdlib.h>

#include <iostream>

#include "drivers/launcher/launch_plan.h"
#include "drivers/launcher/supervisor.h"
#include "runtime/log.h"
#include "runtime/process.h"

namespace {

int Main(int argc, char** argv) {
  using namespace slammtt;
  CommandLine cl("slammtt-launch", "--config FILE [options]",
                 "Starts the processes listed in the robot: section of FILE (drivers, segmenter, "
                 "estimator, lcm-logger), prefixes their output with their names, restarts the "
                 "ones that die, and stops them all on Ctrl-C or SIGTERM.");
  AddStandardOptions(&cl);
  cl.AddFlag("dry-run", "print the command lines and exit");
  cl.AddFlag("options-table",
             "print the tables of the robot: section's settings (Markdown, docs/robot.md) and "
             "exit");
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("options-table")) {
    std::cout << LaunchPlanOptionsTables();
    return 0;
  }
  if (!cl.Value("config")) throw UsageError("--config FILE is required");
  const ProcessSettings settings = LoadProcessSettings(cl);
  const Config robot = settings.config.Child("robot");
  if (!settings.config.Has("robot")) robot.Fail(settings.config_path + ": no robot: section");
  const LaunchPlan plan = ReadLaunchPlan(robot);

  SupervisorSettings supervisor_settings;
  char absolute[PATH_MAX];
  if (realpath(settings.config_path.c_str(), absolute) == nullptr) {
    throw std::runtime_error(settings.config_path + ": cannot resolve the path");
  }
  supervisor_settings.config_path = absolute;
  supervisor_settings.lcm_url = settings.lcm_url;
  supervisor_settings.lcm_url_from_command_line = cl.Value("lcm-url").has_value();
  supervisor_settings.self_directory = SelfDirectory();
  Supervisor supervisor(plan, supervisor_settings);
  if (cl.Flag("dry-run")) {
    for (const auto& line : supervisor.CommandLines()) {
      std::string text;
      for (const std::string& arg : line) text += (text.empty() ? "" : " ") + arg;
      std::cout << text << "\n";
    }
    return 0;
  }
  return supervisor.Run();
}

}  // namespace

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-launch", Main);
}
