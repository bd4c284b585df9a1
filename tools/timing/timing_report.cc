#include "tools/timing/timing_report.h"

#include <cstdio>
#include <optional>
#include <sstream>

namespace slammtt {
namespace {

nlohmann::json StatsJson(const DurationStats& s) {
  return {{"count", s.count}, {"median", s.median}, {"p95", s.p95},
          {"p99", s.p99},     {"max", s.max},       {"mean", s.mean}};
}

template <class T>
nlohmann::json OrNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::string Microseconds(int64_t ns) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", static_cast<double>(ns) * 1e-3);
  return text;
}

std::string DurationRow(const std::string& name, const DurationStats& s) {
  char line[160];
  std::snprintf(line, sizeof(line), "%-26s %8lld %10s %10s %10s %10s", name.c_str(),
                static_cast<long long>(s.count), Microseconds(s.median).c_str(),
                Microseconds(s.p95).c_str(), Microseconds(s.p99).c_str(),
                Microseconds(s.max).c_str());
  return line;
}

std::string CounterRow(const std::string& name, const DurationStats& s) {
  char line[160];
  std::snprintf(line, sizeof(line), "  %-24s %8lld %10lld %10lld %10lld %10lld   (count)",
                ("#" + name).c_str(), static_cast<long long>(s.count),
                static_cast<long long>(s.median), static_cast<long long>(s.p95),
                static_cast<long long>(s.p99), static_cast<long long>(s.max));
  return line;
}

}  // namespace

std::string TimingTableText(const std::vector<StageTimingSummary>& summaries) {
  std::ostringstream out;
  char header[160];
  std::snprintf(header, sizeof(header), "%-26s %8s %10s %10s %10s %10s", "stage / sub-stage",
                "count", "median", "p95", "p99", "max");
  out << header << "   (microseconds)\n";
  for (const StageTimingSummary& s : summaries) {
    out << DurationRow(s.stage, s.total_ns);
    if (s.share_of_period && s.period_median_us && s.load) {
      char share[96];
      std::snprintf(share, sizeof(share), "   %.3f%% of the %.1f ms period, load %.3f%%",
                    100.0 * *s.share_of_period, static_cast<double>(*s.period_median_us) * 1e-3,
                    100.0 * *s.load);
      out << share;
    }
    out << "\n";
    for (const NamedStats& sub : s.substages_ns) {
      out << DurationRow("  " + sub.name, sub.stats) << "\n";
    }
    for (const NamedStats& counter : s.counters) {
      out << CounterRow(counter.name, counter.stats) << "\n";
    }
  }
  return out.str();
}

nlohmann::json TimingJson(const std::vector<StageTimingSummary>& summaries,
                          const std::string& log_path, const std::string& channel,
                          int64_t messages, int64_t skipped_messages) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageTimingSummary& s : summaries) {
    nlohmann::json substages = nlohmann::json::array();
    for (const NamedStats& n : s.substages_ns) {
      substages.push_back({{"name", n.name}, {"ns", StatsJson(n.stats)}});
    }
    nlohmann::json counters = nlohmann::json::array();
    for (const NamedStats& n : s.counters) {
      counters.push_back({{"name", n.name}, {"value", StatsJson(n.stats)}});
    }
    stages.push_back({{"stage", s.stage},
                      {"total_ns", StatsJson(s.total_ns)},
                      {"substages", substages},
                      {"counters", counters},
                      {"period_median_us", OrNull(s.period_median_us)},
                      {"share_of_period", OrNull(s.share_of_period)},
                      {"load", OrNull(s.load)}});
  }
  return {{"log", log_path},
          {"channel", channel},
          {"messages", messages},
          {"skipped_messages", skipped_messages},
          {"stages", stages}};
}

std::string TimingJsonText(const nlohmann::json& report) {
  // Stage and sub-stage names come from the bus: a byte that is no UTF-8 becomes U+FFFD
  // instead of failing the whole report (nlohmann's default throws type_error 316).
  return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace slammtt
