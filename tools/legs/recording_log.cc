#include "tools/legs/recording_log.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/leg_labels_t.hpp"
#include "runtime/log_reader.h"

namespace slammtt {

Recording ReadRecording(const std::string& name, const std::string& path,
                        const std::string& scan_channel, const std::string& labels_channel) {
  Recording recording;
  recording.name = name;
  std::map<int64_t, size_t> scan_of_utime;
  const LogReadResult read = ForEachLogEvent(path, [&](const LogEventView& event) {
    if (event.channel == scan_channel) {
      slammtt_msgs::laser_scan_t msg;
      if (!Decode(event.data, event.size, &msg)) {
        ++recording.undecodable;
        return;
      }
      RecordedScan scan;
      scan.utime = msg.utime;
      scan.angle_rad = msg.angle_rad;
      scan.range_m = msg.range_m;
      scan.valid.assign(msg.valid.begin(), msg.valid.end());
      scan.range_min_m = msg.range_min_m;
      scan.range_max_m = msg.range_max_m;
      scan_of_utime[msg.utime] = recording.scans.size();
      recording.scans.push_back(std::move(scan));
    } else if (event.channel == labels_channel) {
      slammtt_msgs::leg_labels_t msg;
      if (!Decode(event.data, event.size, &msg)) {
        ++recording.undecodable;
        return;
      }
      const auto found = scan_of_utime.find(msg.utime);
      if (found == scan_of_utime.end()) {
        ++recording.labels_without_scan;
        return;
      }
      RecordedScan& scan = recording.scans[found->second];
      scan.labelled = true;
      for (int32_t i = 0; i < msg.num_legs; ++i) scan.labels_m.emplace_back(msg.x_m[i], msg.y_m[i]);
    }
  });
  if (read.corrupt) throw std::runtime_error(read.problem);
  return recording;
}

Recording PartOf(const Recording& recording, double begin, double end) {
  Recording part;
  part.name = recording.name;
  const auto n = static_cast<double>(recording.scans.size());
  const auto first = static_cast<size_t>(std::floor(begin * n));
  const auto last = std::min(recording.scans.size(), static_cast<size_t>(std::floor(end * n)));
  for (size_t i = first; i < last; ++i) part.scans.push_back(recording.scans[i]);
  return part;
}

}  // namespace slammtt
