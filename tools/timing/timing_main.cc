// slammtt-timing LOG.lcm [--json]: where the time goes, per stage and sub-stage, from the
// STAGE_TIMING messages of a log (a live recording or replay's OUT.lcm.timing.lcm). Definitions
// in timing_table.h and docs/tools.md.
#include <iostream>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "tools/timing/timing_log.h"
#include "tools/timing/timing_report.h"
#include "tools/timing/timing_table.h"

namespace slammtt {
namespace {

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-timing", "[options] LOG.lcm",
                 "Per-stage and per-sub-stage timing (count, median, 95th and 99th percentile, "
                 "maximum, share of the sensor period) from the STAGE_TIMING messages of a log.");
  AddStandardOptions(&cl);
  cl.AddPositional("LOG.lcm", "a live recording or the timing log of slammtt-replay");
  cl.AddFlag("json", "print JSON instead of the table");
  if (!cl.Parse(argc, argv)) return 0;
  const std::string path = *cl.Positional("LOG.lcm");
  const ProcessSettings settings = LoadProcessSettings(cl);
  const std::string channel = settings.channels.Get("stage_timing");

  const TimingLog log = ReadTimingLog(path, channel);
  if (log.undecodable > 0) {
    LogWarning() << "skipped " << log.undecodable << " undecodable " << channel << " messages";
  }
  if (log.negative > 0) {
    LogWarning() << "skipped " << log.negative << " " << channel
                 << " messages with negative durations";
  }
  if (log.implausible > 0) {
    LogWarning() << "skipped " << log.implausible << " " << channel
                 << " messages with a duration beyond an hour";
  }
  const std::vector<StageTimingSummary> summaries = SummariseTiming(log.records);
  if (cl.Flag("json")) {
    std::cout << TimingJsonText(TimingJson(summaries, path, channel,
                                           static_cast<int64_t>(log.records.size()),
                                           log.undecodable + log.negative + log.implausible));
  } else if (summaries.empty()) {
    std::cout << "no " << channel << " messages in " << path << "\n";
  } else {
    std::cout << "stage timing of " << path << " (" << log.records.size() << " messages on "
              << channel << ")\n"
              << TimingTableText(summaries);
  }
  if (log.read.corrupt) {
    LogError() << log.read.problem;
    return 1;
  }
  if (!log.read.problem.empty()) LogWarning() << log.read.problem << "; ignored";
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-timing", slammtt::Run);
}
