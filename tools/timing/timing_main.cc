// slammtt-timing LOG.lcm [--json]: where the time goes, per stage and sub-stage, from the
// STAGE_TIMING messages of a log (a live recording or replay's OUT.timing.lcm). Definitions in
// timing_table.h and docs/tools.md.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/lcm_io.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "tools/replay/log_events.h"
#include "tools/timing/timing_table.h"

namespace slammtt {
namespace {

nlohmann::json StatsJson(const DurationStats& s) {
  return {{"count", s.count}, {"median", s.median}, {"p95", s.p95},
          {"p99", s.p99},     {"max", s.max},       {"mean", s.mean}};
}

template <class T>
nlohmann::json Optional(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::string Us(int64_t ns) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", static_cast<double>(ns) * 1e-3);
  return text;
}

std::string Row(const std::string& name, const DurationStats& s) {
  char line[160];
  std::snprintf(line, sizeof(line), "%-26s %8lld %10s %10s %10s %10s", name.c_str(),
                static_cast<long long>(s.count), Us(s.median).c_str(), Us(s.p95).c_str(),
                Us(s.p99).c_str(), Us(s.max).c_str());
  return line;
}

std::string TextTable(const std::vector<StageTimingSummary>& summaries) {
  std::ostringstream out;
  char header[160];
  std::snprintf(header, sizeof(header), "%-26s %8s %10s %10s %10s %10s", "stage / sub-stage",
                "count", "median", "p95", "p99", "max");
  out << header << "   (microseconds)\n";
  for (const StageTimingSummary& s : summaries) {
    out << Row(s.stage, s.total_ns);
    if (s.share_of_period) {
      char share[96];
      std::snprintf(share, sizeof(share), "   %.3f%% of the %.1f ms period, load %.3f%%",
                    100.0 * *s.share_of_period,
                    static_cast<double>(*s.period_median_us) * 1e-3, 100.0 * *s.load);
      out << share;
    }
    out << "\n";
    for (const NamedStats& sub : s.substages_ns) out << Row("  " + sub.name, sub.stats) << "\n";
    for (const NamedStats& counter : s.counters) {
      char line[160];
      std::snprintf(line, sizeof(line), "  %-24s %8lld %10lld %10lld %10lld %10lld   (count)",
                    ("#" + counter.name).c_str(), static_cast<long long>(counter.stats.count),
                    static_cast<long long>(counter.stats.median),
                    static_cast<long long>(counter.stats.p95),
                    static_cast<long long>(counter.stats.p99),
                    static_cast<long long>(counter.stats.max));
      out << line << "\n";
    }
  }
  return out.str();
}

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

  std::vector<TimingRecord> records;
  int64_t undecodable = 0;
  int64_t negative = 0;
  const LogReadResult read = ForEachLogEvent(path, [&](const LogEventView& e) {
    if (e.channel != channel) return;
    slammtt_msgs::stage_timing_t msg;
    if (!Decode(e.data, e.size, &msg) ||
        static_cast<size_t>(msg.num_substages) != msg.substage.size() ||
        static_cast<size_t>(msg.num_counters) != msg.counter_name.size()) {
      ++undecodable;
      return;
    }
    bool bad = msg.total_ns < 0;
    for (int64_t ns : msg.substage_ns) bad = bad || ns < 0;
    if (bad) {
      ++negative;
      return;
    }
    TimingRecord r;
    r.utime = msg.utime;
    r.stage = msg.stage;
    r.total_ns = msg.total_ns;
    for (int k = 0; k < msg.num_substages; ++k) {
      r.substages_ns.emplace_back(msg.substage[k], msg.substage_ns[k]);
    }
    for (int k = 0; k < msg.num_counters; ++k) {
      r.counters.emplace_back(msg.counter_name[k], msg.counter_value[k]);
    }
    records.push_back(std::move(r));
  });
  if (undecodable > 0) {
    LogWarning() << "skipped " << undecodable << " undecodable " << channel << " messages";
  }
  if (negative > 0) {
    LogWarning() << "skipped " << negative << " " << channel << " messages with negative durations";
  }
  const std::vector<StageTimingSummary> summaries = SummariseTiming(records);

  if (cl.Flag("json")) {
    nlohmann::json stages = nlohmann::json::array();
    for (const StageTimingSummary& s : summaries) {
      nlohmann::json sub = nlohmann::json::array();
      for (const NamedStats& n : s.substages_ns) {
        sub.push_back({{"name", n.name}, {"ns", StatsJson(n.stats)}});
      }
      nlohmann::json counters = nlohmann::json::array();
      for (const NamedStats& n : s.counters) {
        counters.push_back({{"name", n.name}, {"value", StatsJson(n.stats)}});
      }
      stages.push_back({{"stage", s.stage},
                        {"total_ns", StatsJson(s.total_ns)},
                        {"substages", sub},
                        {"counters", counters},
                        {"period_median_us", Optional(s.period_median_us)},
                        {"share_of_period", Optional(s.share_of_period)},
                        {"load", Optional(s.load)}});
    }
    const nlohmann::json report = {{"log", path},
                                   {"channel", channel},
                                   {"messages", static_cast<int64_t>(records.size())},
                                   {"skipped_messages", undecodable + negative},
                                   {"stages", stages}};
    std::cout << report.dump(2) << "\n";
  } else {
    if (summaries.empty()) {
      std::cout << "no " << channel << " messages in " << path << "\n";
    } else {
      std::cout << "stage timing of " << path << " (" << records.size() << " messages on "
                << channel << ")\n"
                << TextTable(summaries);
    }
  }
  if (!read.problem.empty()) {
    if (read.corrupt) {
      LogError() << read.problem;
      return 1;
    }
    LogWarning() << read.problem;
  }
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-timing", slammtt::Run);
}
