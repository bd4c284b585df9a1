// slammtt-replay IN.lcm -o OUT.lcm [--config FILE]: deterministic replay of a log through the
// processing stages (log_replay.h; usage and semantics in docs/tools.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"
#include "tools/replay/log_replay.h"
#include "tools/replay/replay_config.h"
#include "tools/replay/stack_stages.h"

namespace slammtt {
namespace {

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-replay", "[options] IN.lcm -o OUT.lcm",
                 "Runs the processing stages on a log in log order and writes a log with the "
                 "inputs and every output, byte-identical on every run. Stage timing goes to a "
                 "separate log (OUT.lcm.timing.lcm by default).");
  AddStandardOptions(&cl);
  cl.AddPositional("IN.lcm", "input log (lcm-logger or slammtt-world)",
                   /*required=*/false);  // not with --options-table
  cl.AddOption("output", "OUT.lcm", "output log (required)", 'o');
  cl.AddOption("timing-log", "FILE", "STAGE_TIMING log (default: OUT.lcm.timing.lcm)");
  cl.AddFlag("no-timing", "write no timing log");
  cl.AddRepeatedOption("stage", "NAME",
                       "run only these stages (segmenter, estimator, smoother; overrides "
                       "replay.stages)");
  cl.AddFlag("smoother",
            "run the smoother as well (slammtt-smoother; as a `smoother:` section does)");
  cl.AddRepeatedOption("drop-channel", "CHANNEL",
                       "leave this channel of the input out: not copied, not handed to any "
                       "stage (e.g. ODOMETRY: a robot without wheel odometry)");
  cl.AddFlag("strict", "treat a truncated final event as an error (default: a warning)");
  cl.AddFlag("options-table",
             "print the table of the replay: section's settings (Markdown, docs/tools.md) and "
             "exit");
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("options-table")) {
    std::cout << ReplayOptionsTable();
    return 0;
  }
  if (!cl.Positional("IN.lcm")) throw UsageError("missing argument IN.lcm (see --help)");
  const std::string input = *cl.Positional("IN.lcm");
  const auto output = cl.Value("output");
  if (!output) throw UsageError("-o OUT.lcm is required");
  if (cl.Flag("no-timing") && cl.Value("timing-log")) {
    throw UsageError("--no-timing and --timing-log exclude each other");
  }

  ProcessSettings settings = LoadProcessSettings(cl);
  const ReplaySettings replay =
      ReadReplaySettings(settings.config.Child("replay"), DefaultStackStages(settings.config));
  ReplayFileOptions options = replay.file_options;
  std::vector<std::string> enabled = cl.Values("stage").empty() ? replay.stages : cl.Values("stage");
  if (cl.Flag("smoother") &&
      std::find(enabled.begin(), enabled.end(), "smoother") == enabled.end()) {
    enabled.push_back("smoother");
  }
  if (cl.Flag("strict")) options.truncated_tail_is_error = true;
  for (const std::string& channel : cl.Values("drop-channel")) {
    options.dropped_channels.insert(channel);
  }
  options.timing_channel = settings.channels.Get("stage_timing");
  if (!cl.Flag("no-timing")) {
    options.timing_path = cl.ValueOr("timing-log", *output + ".timing.lcm");
  }
  // The steady clock only paces and annotates the progress line; no output depends on it.
  const auto start = std::chrono::steady_clock::now();
  options.on_progress = [&](const ReplayProgress& p) {
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double log_s = static_cast<double>(p.log_time_us) * 1e-6;
    LogInfo() << "replay: " << p.events_done << "/" << p.events_total << " events, "
              << static_cast<int64_t>(log_s) << " of "
              << static_cast<int64_t>(static_cast<double>(p.log_span_us) * 1e-6)
              << " s of log, " << static_cast<int64_t>(wall_s > 0 ? log_s / wall_s : 0.0)
              << "x real time";
  };

  // SIGINT/SIGTERM (ProcessMain's handlers): stop at the next event, leave no output.
  options.should_stop = [] { return ShutdownRequested(); };
  std::vector<std::unique_ptr<Stage>> stages = CreateStackStages(settings, enabled);
  if (settings.config_path.empty()) {
    // An input that cannot be scanned is reported by ReplayLogFile, in its one line.
    std::string line;
    try {
      line = DefaultsLine(ScanLogFile(input), settings.channels, enabled);
    } catch (const std::runtime_error&) {
    }
    if (!line.empty()) LogInfo() << line;
  }
  const ReplayFileResult result = ReplayLogFile(input, *output, std::move(stages), options);
  for (const StageReplayStats& s : result.stages) {
    if (!s.runs) {
      LogInfo() << s.name << ": skipped (none of its input channels is in the log)";
      continue;
    }
    LogInfo() << s.name << ": handled " << s.messages_handled << " messages, published "
              << s.messages_published << (s.errors > 0 ? ", " : "")
              << (s.errors > 0 ? std::to_string(s.errors) + " failed" : "");
  }
  if (!result.warning.empty()) LogWarning() << result.warning;
  if (!result.error.empty()) {
    LogError() << result.error
               << (ShutdownRequested() ? " (signal " + std::to_string(ShutdownSignal()) + ")"
                                       : std::string())
               << "; no output written";
    return 1;
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double span_s =
      static_cast<double>(result.input.last_timestamp_us - result.input.first_timestamp_us) * 1e-6;
  LogInfo() << "wrote " << result.events_written << " events to " << *output
            << (options.timing_path.empty()
                    ? std::string()
                    : " and " + std::to_string(result.timing_events_written) + " to " +
                          options.timing_path)
            << " (" << span_s << " s of log in " << wall_s << " s)";
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-replay", slammtt::Run);
}
