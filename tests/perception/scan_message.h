// A TestScan as the laser_scan_t a driver publishes: for the tests of the stage adapter and of
// the slammtt-segmenter process.
#pragma once

#include <cstdint>

#include "slammtt_msgs/laser_scan_t.hpp"
#include "tests/perception/synthetic_scan.h"

namespace slammtt {
namespace testing_support {

// 100 ms per revolution and the RPLIDAR A2's range limits (0.15-12 m), intensity 1 everywhere.
inline slammtt_msgs::laser_scan_t ScanMessage(const TestScan& scan, int64_t utime,
                                              int64_t sequence) {
  slammtt_msgs::laser_scan_t msg;
  msg.utime = utime;
  msg.sequence = sequence;
  msg.scan_duration_us = 100000;
  msg.range_min_m = 0.15f;
  msg.range_max_m = 12.0f;
  msg.num_beams = static_cast<int32_t>(scan.size());
  msg.angle_rad = scan.angle_rad;
  msg.range_m = scan.range_m;
  msg.intensity.assign(scan.size(), 1.0f);
  msg.valid = scan.valid;
  return msg;
}

}  // namespace testing_support
}  // namespace slammtt
