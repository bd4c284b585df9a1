// Reads an imported recording (slammtt-import's LCM log: LASER_SCAN and LEG_LABELS) into
// memory for the leg classifier's training and evaluation (tools/legs).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/legs/leg_dataset.h"

namespace slammtt {

struct Recording {
  std::string name;
  std::vector<RecordedScan> scans;  // in log order
  int64_t undecodable = 0;          // events on the two channels that did not decode
  int64_t labels_without_scan = 0;  // LEG_LABELS whose utime is no scan's
};

// Every laser_scan_t of `scan_channel`, with the leg_labels_t of `labels_channel` whose utime
// is the scan's (the importer writes a scan's labels with the scan's utime). Throws
// std::runtime_error when the file cannot be read or is corrupt (a truncated final event is
// accepted: every complete event is used).
Recording ReadRecording(const std::string& name, const std::string& path,
                        const std::string& scan_channel = "LASER_SCAN",
                        const std::string& labels_channel = "LEG_LABELS");

// The scans [floor(begin n), floor(end n)) of a recording of n scans (0 <= begin < end <= 1):
// a part of a recording in time, e.g. the first half for training and the second for testing.
Recording PartOf(const Recording& recording, double begin, double end);

}  // namespace slammtt
