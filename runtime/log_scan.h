// A structural pass over an LCM event log, without decoding any message: which channels it
// holds, how many events, which time span, and whether (and where) it is damaged.
//
// The layout walked here is LCM's log file format (LCM documentation, "LCM Log File Format"):
// every event is a 28-byte header - sync word 0xEDA1DA01, int64 event number, int64 timestamp
// [us], int32 channel length, int32 data length, all big-endian - followed by the channel name
// and the data. The events themselves are read by LCM's own event-log API (lcm::LogFile), so a
// replay sees exactly what lcm-logplayer plays; this scan only learns the channels up front and
// explains why LCM's reader stopped where it did.
//
// Damage comes in two kinds:
// - truncated tail: the bytes after the last complete event are the beginning of an event that
//   the file ends inside of (what a logger killed mid-write leaves behind);
// - corrupt: a bad sync word or impossible lengths before the end. LCM's reader stops there
//   (and also drops the event just before, whose trailing sync check fails).
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace slammtt {

enum class LogDamage { kNone, kTruncatedTail, kCorrupt };

struct ChannelSummary {
  int64_t events = 0;
  int64_t bytes = 0;
  int64_t first_timestamp_us = 0;
  int64_t last_timestamp_us = 0;
};

struct LogScan {
  int64_t file_size = 0;
  int64_t complete_events = 0;    // events before any damage
  int64_t valid_bytes = 0;        // offset where the complete events end
  int64_t first_timestamp_us = 0;
  int64_t last_timestamp_us = 0;
  std::map<std::string, ChannelSummary> channels;
  LogDamage damage = LogDamage::kNone;
  // One line without the path, e.g. "corrupt event header at byte 4711 (bad sync word)";
  // empty when there is no damage.
  std::string damage_description;
};

// Scans `path`. Throws std::runtime_error, one line naming the path, when it cannot be opened
// or is not a regular file (a directory, /dev/zero, a FIFO).
LogScan ScanLogFile(const std::string& path);

}  // namespace slammtt
