#include "tools/timing/timing_table.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "common/utime.h"

namespace slammtt {
namespace {

int64_t NearestRank(const std::vector<int64_t>& sorted, double q) {
  const double n = static_cast<double>(sorted.size());
  size_t rank = static_cast<size_t>(std::ceil(q * n));
  rank = std::clamp<size_t>(rank, 1, sorted.size());
  return sorted[rank - 1];
}

// Accumulates named series in order of first appearance.
class NamedSeries {
 public:
  void Add(const std::string& name, int64_t value) {
    auto it = index_.find(name);
    if (it == index_.end()) {
      it = index_.emplace(name, names_.size()).first;
      names_.push_back(name);
      values_.emplace_back();
    }
    values_[it->second].push_back(value);
  }
  std::vector<NamedStats> Stats() const {
    std::vector<NamedStats> out;
    for (size_t k = 0; k < names_.size(); ++k) out.push_back({names_[k], ComputeStats(values_[k])});
    return out;
  }

 private:
  std::map<std::string, size_t> index_;
  std::vector<std::string> names_;
  std::vector<std::vector<int64_t>> values_;
};

}  // namespace

DurationStats ComputeStats(std::vector<int64_t> values) {
  DurationStats stats;
  if (values.empty()) return stats;
  std::sort(values.begin(), values.end());
  stats.count = static_cast<int64_t>(values.size());
  stats.median = NearestRank(values, 0.5);
  stats.p95 = NearestRank(values, 0.95);
  stats.p99 = NearestRank(values, 0.99);
  stats.max = values.back();
  // The sum saturates at the ends of int64 (slammtt-timing skips durations beyond an hour, but
  // this function takes any values); the mean is summed in double, which cannot overflow here.
  double total = 0.0;
  for (int64_t v : values) {
    total += static_cast<double>(v);
    if (__builtin_add_overflow(stats.sum, v, &stats.sum)) {
      stats.sum = v > 0 ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
    }
  }
  stats.mean = total / static_cast<double>(stats.count);
  return stats;
}

std::vector<StageTimingSummary> SummariseTiming(const std::vector<TimingRecord>& records) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const TimingRecord*>> by_stage;
  for (const TimingRecord& r : records) {
    auto& list = by_stage[r.stage];
    if (list.empty()) order.push_back(r.stage);
    list.push_back(&r);
  }
  std::vector<StageTimingSummary> summaries;
  for (const std::string& stage : order) {
    const auto& list = by_stage.at(stage);
    StageTimingSummary summary;
    summary.stage = stage;
    std::vector<int64_t> totals;
    std::vector<int64_t> utimes;
    NamedSeries substages;
    NamedSeries counters;
    for (const TimingRecord* r : list) {
      totals.push_back(r->total_ns);
      utimes.push_back(r->utime);
      for (const auto& [name, ns] : r->substages_ns) substages.Add(name, ns);
      for (const auto& [name, value] : r->counters) counters.Add(name, value);
    }
    summary.total_ns = ComputeStats(totals);
    summary.substages_ns = substages.Stats();
    summary.counters = counters.Stats();
    std::sort(utimes.begin(), utimes.end());
    utimes.erase(std::unique(utimes.begin(), utimes.end()), utimes.end());
    if (utimes.size() >= 2) {
      std::vector<int64_t> intervals;
      for (size_t k = 1; k < utimes.size(); ++k) {
        int64_t interval = 0;  // utimes from a damaged log may lie further apart than int64
        if (__builtin_sub_overflow(utimes[k], utimes[k - 1], &interval)) {
          interval = std::numeric_limits<int64_t>::max();
        }
        intervals.push_back(interval);
      }
      summary.period_median_us = ComputeStats(intervals).median;
      summary.share_of_period = static_cast<double>(summary.total_ns.median) /
                                (static_cast<double>(*summary.period_median_us) * 1e3);
      const double span_ns = MicrosecondsBetween(utimes.back(), utimes.front()) * 1e3;
      summary.load = static_cast<double>(summary.total_ns.sum) / span_ns;
    }
    summaries.push_back(summary);
  }
  return summaries;
}

}  // namespace slammtt
