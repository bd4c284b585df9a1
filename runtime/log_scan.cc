#include "runtime/log_scan.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <array>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

namespace slammtt {
namespace {

constexpr uint32_t kSyncWord = 0xEDA1DA01u;
constexpr int64_t kHeaderBytes = 28;
// LCM refuses channel names of 1000 bytes or more when it reads a log (eventlog.c).
constexpr int32_t kMaxChannelLength = 1000;

uint64_t BigEndian(const uint8_t* bytes, int count) {
  uint64_t value = 0;
  for (int k = 0; k < count; ++k) value = (value << 8) | bytes[k];
  return value;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// The offset of the first plausible complete event header at or after `from` (a sync word,
// channel and data lengths LCM accepts, and an event that ends inside the file), or -1. Tells a
// truncated tail (nothing follows) from a damaged length field (more events follow).
int64_t FindNextEventHeader(std::FILE* file, int64_t from, int64_t file_size) {
  constexpr size_t kChunk = 1 << 16;
  std::vector<uint8_t> buffer(kChunk + kHeaderBytes);
  for (int64_t chunk_start = from; chunk_start + kHeaderBytes <= file_size;
       chunk_start += kChunk) {
    if (std::fseek(file, static_cast<long>(chunk_start), SEEK_SET) != 0) return -1;
    const size_t n = std::fread(buffer.data(), 1, buffer.size(), file);
    for (size_t k = 0; k + kHeaderBytes <= n && k < kChunk; ++k) {
      if (BigEndian(&buffer[k], 4) != kSyncWord) continue;
      const int32_t channel_length = static_cast<int32_t>(BigEndian(&buffer[k + 20], 4));
      const int32_t data_length = static_cast<int32_t>(BigEndian(&buffer[k + 24], 4));
      if (channel_length <= 0 || channel_length >= kMaxChannelLength || data_length < 0) continue;
      const int64_t at = chunk_start + static_cast<int64_t>(k);
      if (at + kHeaderBytes + channel_length + data_length <= file_size) return at;
    }
  }
  return -1;
}

}  // namespace

LogScan ScanLogFile(const std::string& path) {
  // A log is a regular file: a directory reads as an empty log (exit 0 with nothing done), and
  // LCM's reader spins forever on /dev/zero looking for a sync word. O_NONBLOCK keeps the open
  // of a FIFO from waiting for a writer.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) {
    throw std::runtime_error(path + ": cannot open log file: " + std::strerror(errno));
  }
  struct stat info {};
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    throw std::runtime_error(path + ": not a log file (not a regular file)");
  }
  std::unique_ptr<std::FILE, FileCloser> file(fdopen(fd, "rb"));
  if (!file) {
    close(fd);
    throw std::runtime_error(path + ": cannot open log file");
  }
  LogScan scan;
  if (std::fseek(file.get(), 0, SEEK_END) != 0) throw std::runtime_error(path + ": cannot seek");
  scan.file_size = static_cast<int64_t>(std::ftell(file.get()));
  std::rewind(file.get());

  int64_t offset = 0;
  std::array<uint8_t, kHeaderBytes> header{};
  std::string channel;
  while (offset < scan.file_size) {
    const int64_t remaining = scan.file_size - offset;
    const size_t header_read = std::fread(header.data(), 1, header.size(), file.get());
    // How much of the sync word is present and right?
    const int sync_bytes = static_cast<int>(std::min<size_t>(header_read, 4));
    bool sync_ok = true;
    for (int k = 0; k < sync_bytes; ++k) {
      sync_ok = sync_ok && header[k] == static_cast<uint8_t>(kSyncWord >> (24 - 8 * k));
    }
    if (!sync_ok) {
      scan.damage = LogDamage::kCorrupt;
      scan.damage_description =
          "corrupt event header at byte " + std::to_string(offset) + " (bad sync word)";
      break;
    }
    if (static_cast<int64_t>(header_read) < kHeaderBytes) {
      scan.damage = LogDamage::kTruncatedTail;
      scan.damage_description = "truncated final event at byte " + std::to_string(offset) +
                                " (" + std::to_string(remaining) + " of at least " +
                                std::to_string(kHeaderBytes) + " header bytes present)";
      break;
    }
    const int64_t timestamp = static_cast<int64_t>(BigEndian(&header[12], 8));
    const int32_t channel_length = static_cast<int32_t>(BigEndian(&header[20], 4));
    const int32_t data_length = static_cast<int32_t>(BigEndian(&header[24], 4));
    if (channel_length <= 0 || channel_length >= kMaxChannelLength || data_length < 0) {
      scan.damage = LogDamage::kCorrupt;
      scan.damage_description = "corrupt event header at byte " + std::to_string(offset) +
                                " (channel length " + std::to_string(channel_length) +
                                ", data length " + std::to_string(data_length) + ")";
      break;
    }
    const int64_t event_bytes = kHeaderBytes + channel_length + data_length;
    if (event_bytes > remaining) {
      const int64_t next = FindNextEventHeader(file.get(), offset + 4, scan.file_size);
      if (next >= 0) {
        scan.damage = LogDamage::kCorrupt;
        scan.damage_description = "corrupt event header at byte " + std::to_string(offset) +
                                  " (it runs " + std::to_string(event_bytes - remaining) +
                                  " bytes past the end, but an event follows at byte " +
                                  std::to_string(next) + ")";
        break;
      }
      scan.damage = LogDamage::kTruncatedTail;
      scan.damage_description = "truncated final event at byte " + std::to_string(offset) +
                                " (" + std::to_string(remaining) + " of " +
                                std::to_string(event_bytes) + " bytes present)";
      break;
    }
    channel.resize(static_cast<size_t>(channel_length));
    if (std::fread(channel.data(), 1, channel.size(), file.get()) != channel.size() ||
        std::fseek(file.get(), data_length, SEEK_CUR) != 0) {
      throw std::runtime_error(path + ": read error at byte " + std::to_string(offset));
    }
    ChannelSummary& summary = scan.channels[channel];
    if (summary.events == 0) summary.first_timestamp_us = timestamp;
    summary.last_timestamp_us = timestamp;
    ++summary.events;
    summary.bytes += data_length;
    if (scan.complete_events == 0) scan.first_timestamp_us = timestamp;
    scan.last_timestamp_us = timestamp;
    ++scan.complete_events;
    offset += event_bytes;
    scan.valid_bytes = offset;
  }
  return scan;
}

}  // namespace slammtt
