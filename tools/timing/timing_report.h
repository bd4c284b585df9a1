// slammtt-timing's two outputs from the per-stage summaries of timing_table.h (pure: strings and
// JSON, no I/O). Durations in the table are microseconds with one decimal; in JSON nanoseconds.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "tools/timing/timing_table.h"

namespace slammtt {

// The table people read: one row per stage (count, median, p95, p99, max in microseconds, then
// the share of the sensor period and the load), its sub-stages indented below it, and its work
// counters as "#name" rows (plain counts).
std::string TimingTableText(const std::vector<StageTimingSummary>& summaries);

// {"log", "channel", "messages", "skipped_messages", "stages": [{"stage", "total_ns": {count,
// median, p95, p99, max, mean}, "substages": [{"name", "ns"}], "counters": [{"name", "value"}],
// "period_median_us", "share_of_period", "load"}]}; absent figures are null.
nlohmann::json TimingJson(const std::vector<StageTimingSummary>& summaries,
                          const std::string& log_path, const std::string& channel,
                          int64_t messages, int64_t skipped_messages);

// The JSON as slammtt-timing prints it: indented by 2, a newline at the end; a name with bytes
// that are no UTF-8 (stage names come from the bus) has each replaced by U+FFFD.
std::string TimingJsonText(const nlohmann::json& report);

}  // namespace slammtt
