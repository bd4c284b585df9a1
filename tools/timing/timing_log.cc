#include "tools/timing/timing_log.h"

#include <utility>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/stage_timing_t.hpp"

namespace slammtt {

TimingLog ReadTimingLog(const std::string& path, const std::string& channel) {
  TimingLog log;
  log.read = ForEachLogEvent(path, [&](const LogEventView& e) {
    if (e.channel != channel) return;
    slammtt_msgs::stage_timing_t msg;
    if (!Decode(e.data, e.size, &msg)) {
      ++log.undecodable;
      return;
    }
    bool negative = msg.total_ns < 0;
    for (int64_t ns : msg.substage_ns) negative = negative || ns < 0;
    if (negative) {
      ++log.negative;
      return;
    }
    bool implausible = msg.total_ns > kMaxPlausibleDurationNs;
    for (int64_t ns : msg.substage_ns) implausible = implausible || ns > kMaxPlausibleDurationNs;
    if (implausible) {
      ++log.implausible;
      return;
    }
    TimingRecord r;
    r.utime = msg.utime;
    r.stage = std::move(msg.stage);
    r.total_ns = msg.total_ns;
    // Decode leaves num_substages == substage.size() == substage_ns.size() (and likewise for the
    // counters): the generated decoder sizes every array by its count.
    for (size_t k = 0; k < msg.substage.size(); ++k) {
      r.substages_ns.emplace_back(std::move(msg.substage[k]), msg.substage_ns[k]);
    }
    for (size_t k = 0; k < msg.counter_name.size(); ++k) {
      r.counters.emplace_back(std::move(msg.counter_name[k]), msg.counter_value[k]);
    }
    log.records.push_back(std::move(r));
  });
  return log;
}

}  // namespace slammtt
