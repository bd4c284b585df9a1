// slammtt-world: the synthetic world as a program (docs/world.md).
//   slammtt-world --scenario s1-crossing --seed 7 --log OUT.lcm   # as fast as possible
//   slammtt-world --scenario rplidar-a2                            # live, real time
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "tools/world/scenario_loader.h"
#include "tools/world/scenario_options.h"
#include "tools/world/scenario_report.h"
#include "tools/world/world_runner.h"

namespace {

std::string Summary(const std::string& scenario, uint64_t seed, const std::string& where,
                    const slammtt::WorldRunSummary& s) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << scenario << " seed " << seed << ": " << s.messages
      << " messages (";
  bool first = true;
  for (const auto& [channel, count] : s.messages_per_channel) {
    out << (first ? "" : ", ") << channel << " " << count;
    first = false;
  }
  out << ") for " << s.simulated_s << " s simulated in " << s.wall_s << " s wall " << where;
  return out.str();
}

int Run(int argc, char** argv) {
  slammtt::CommandLine cl(
      "slammtt-world", "--scenario NAME|PATH [--seed N] [--log OUT.lcm] [options]",
      "The synthetic world: a robot, a laser and moving people from a scenario file. Writes "
      "ODOMETRY, GROUND_TRUTH and LASER_SCAN and/or FEATURES into an LCM log as fast as "
      "possible (--log), or publishes them live in real time.");
  slammtt::AddStandardOptions(&cl);
  cl.AddOption("scenario", "NAME|PATH",
               "scenario: a name from config/scenarios/ (s1-crossing, s2-lobby, s3-no-static, "
               "rplidar-a2, crowd-zara02) or a YAML file",
               's');
  cl.AddOption("seed", "N", "random seed, a whole number >= 0 (default 1)");
  cl.AddOption("log", "OUT.lcm", "write an LCM log as fast as possible instead of publishing live");
  cl.AddOption("output", "features|scans|both", "sensor output (default: the scenario's)");
  cl.AddOption("duration", "S", "simulated seconds (default: the scenario's duration_s)");
  cl.AddOption("rate-factor", "F", "live mode: run F times faster than real time (default 1)");
  cl.AddFlag("report",
             "print what the scenario offers an estimator (visibility, occlusions, closest "
             "approaches per mover) and exit without publishing");
  cl.AddFlag("follow-commands",
             "live mode: drive the robot from VELOCITY_COMMAND (it stops 0.5 s after the last "
             "command) instead of the scenario's motion");
  cl.AddFlag("options-table",
             "print the tables of a scenario file's settings (Markdown, docs/world.md) and exit");
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("options-table")) {
    std::cout << slammtt::ScenarioOptionsMarkdown();
    return 0;
  }
  const slammtt::ProcessSettings settings = slammtt::LoadProcessSettings(cl);

  const auto scenario_arg = cl.Value("scenario");
  if (!scenario_arg) throw slammtt::UsageError("--scenario is required (see --help)");
  const int64_t seed = cl.IntValue("seed").value_or(1);
  if (seed < 0) throw slammtt::UsageError("--seed must be a whole number >= 0");
  const auto log_path = cl.Value("log");
  const double rate_factor = cl.DoubleValue("rate-factor").value_or(1.0);
  if (!(rate_factor > 0.0)) throw slammtt::UsageError("--rate-factor must be positive");
  if (log_path && (cl.Value("rate-factor") || cl.Flag("follow-commands"))) {
    throw slammtt::UsageError("--rate-factor and --follow-commands are for live mode, not --log");
  }
  if (cl.Flag("report") && (log_path || cl.Value("rate-factor") || cl.Flag("follow-commands"))) {
    throw slammtt::UsageError("--report only prints figures: it takes no --log, --rate-factor or "
                              "--follow-commands");
  }

  // The whole scenario (and any trajectory file) is read and checked before any output exists.
  const std::string path = slammtt::ResolveScenarioPath(
      *scenario_arg, slammtt::ScenarioSearchRoots(SLAMMTT_WORLD_SOURCE_DIR));
  slammtt::Scenario scenario = slammtt::LoadScenario(path);
  if (const auto output = cl.Value("output")) {
    if (!slammtt::ParseSensorOutput(*output, &scenario.output)) {
      throw slammtt::UsageError("--output expects features, scans or both, got '" + *output + "'");
    }
  }
  if (const auto duration = cl.DoubleValue("duration")) {
    if (!(*duration > 0.0) || *duration > slammtt::kMaxScenarioDurationS) {
      throw slammtt::UsageError("--duration must be within (0, 1e6] seconds");
    }
    scenario.duration_s = *duration;
  }
  slammtt::WorldSimulator world(scenario, static_cast<uint64_t>(seed), scenario.output);
  if (cl.Flag("report")) {
    std::cout << scenario.name << " seed " << seed << " output "
              << slammtt::SensorOutputName(scenario.output) << " duration " << scenario.duration_s
              << " s\n"
              << slammtt::FormatScenarioReport(
                     slammtt::ReportScenario(scenario, static_cast<uint64_t>(seed)));
    return 0;
  }

  slammtt::WorldChannels channels;
  channels.odometry = settings.channels.Get("odometry");
  channels.ground_truth = settings.channels.Get("ground_truth");
  channels.laser_scan = settings.channels.Get("laser_scan");
  channels.laser_geometry = settings.channels.Get("laser_geometry");
  channels.features = settings.channels.Get("features");

  slammtt::WorldRunSummary summary;
  std::string where;
  if (log_path) {
    summary = slammtt::WriteWorldLog(&world, channels, *log_path);
    where = "into " + *log_path;
    if (summary.interrupted) {
      slammtt::LogError() << "interrupted: no log written";
      return 1;
    }
  } else {
    slammtt::LcmBus bus(settings.lcm_url);
    slammtt::SteadyMonotonicClock clock;
    slammtt::EventLoop loop(&bus, &clock);
    slammtt::LiveOptions options;
    options.rate_factor = rate_factor;
    options.follow_commands = cl.Flag("follow-commands");
    options.velocity_command_channel = settings.channels.Get("velocity_command");
    summary = slammtt::PublishWorldLive(&world, &loop, channels, options);
    where = "on " + settings.lcm_url + (summary.interrupted ? " (interrupted)" : "");
  }
  slammtt::LogInfo() << Summary(scenario.name, static_cast<uint64_t>(seed), where, summary);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return slammtt::ProcessMain(argc, argv, "slammtt-world", Run); }
