// Where the time goes: per-stage and per-sub-stage statistics of STAGE_TIMING records (pure: no
// LCM, no files; the slammtt-timing program decodes the log and prints the table).
//
// Quantiles are nearest-rank (the q-quantile of n sorted values is the value of rank
// ceil(q * n), 1-based), so every figure in the table is a duration that was actually measured;
// the median of an even count is the lower of the two middle values.
//
// Share of the sensor period: the stage's median total duration divided by its median period,
// the median interval between consecutive distinct utimes of its records (the period of the
// input it is timed on, e.g. 125 ms for 8 scans per second). Load: the sum of all its durations
// divided by the time its records span, the fraction of one core it kept busy on average.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace slammtt {

// One STAGE_TIMING message, decoded.
struct TimingRecord {
  int64_t utime = 0;
  std::string stage;
  int64_t total_ns = 0;
  std::vector<std::pair<std::string, int64_t>> substages_ns;
  std::vector<std::pair<std::string, int64_t>> counters;
};

struct DurationStats {
  int64_t count = 0;
  int64_t median = 0;
  int64_t p95 = 0;
  int64_t p99 = 0;
  int64_t max = 0;
  double mean = 0.0;
  int64_t sum = 0;  // saturated at the ends of int64
};

struct NamedStats {
  std::string name;
  DurationStats stats;
};

struct StageTimingSummary {
  std::string stage;
  DurationStats total_ns;
  std::vector<NamedStats> substages_ns;  // in order of first appearance
  std::vector<NamedStats> counters;      // work counts per message, same statistics
  std::optional<int64_t> period_median_us;  // absent with fewer than two distinct utimes
  std::optional<double> share_of_period;    // median total / median period
  std::optional<double> load;               // sum of totals / span of utimes
};

// Nearest-rank statistics of `values` (any order); all zero for an empty input.
DurationStats ComputeStats(std::vector<int64_t> values);

// One summary per stage, in order of first appearance. Records with a negative duration are
// the caller's to reject (see slammtt-timing), here they are counted like any other.
std::vector<StageTimingSummary> SummariseTiming(const std::vector<TimingRecord>& records);

}  // namespace slammtt
