// LCM plumbing shared by every process and tool: the bus URL, encoding, a sink that stages
// publish into (the bus live, bus.h; a log file in replay), and log files written so that an
// error never leaves a partial log behind (log_reader.h reads them).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "runtime/message_checks.h"
#include "runtime/output_file.h"

namespace slammtt {

// Our default bus: LCM's own default group and port, with ttl=0 so that no packet leaves the
// host unless a user asks for a LAN URL.
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

// The URL to use: the command line if given, else the configuration's lcm.url, else the
// environment's LCM_DEFAULT_URL, else kDefaultLcmUrl.
std::string ResolveLcmUrl(const std::optional<std::string>& from_command_line,
                          const std::optional<std::string>& from_config);

// Opens the bus; throws std::runtime_error with a one-line explanation when the URL is not one
// ParseLcmUrl accepts (runtime/lcm_url.h: LCM itself would take "?ttl=abc" as ttl 0, "?ttl=300"
// as 44 and ignore "?tll=0") or when LCM cannot start (with the fix for the usual cause, a host
// without a multicast route).
std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url);

// Encodes any lcm-gen type.
template <class Msg>
std::vector<uint8_t> Encode(const Msg& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Decodes any lcm-gen type from untrusted bytes (the bus, a log). True only when `data` holds
// exactly one whole message of type Msg in exactly `size` bytes; then *message is replaced.
// False for anything else (wrong type, truncated, trailing bytes, a corrupt array count or
// string length), and *message is left untouched. Never throws.
//
// The type's structural check (runtime/message_checks.h) runs first, because LCM 1.3.1's
// generated decoder allocates whatever array counts the bytes claim before checking them; the
// decoder itself then runs inside try/catch as a second line. Decoding goes into a fresh message,
// because the generated decoder leaves an array untouched when its count is 0: decoding into a
// reused message would keep the previous message's elements.
template <class Msg>
bool Decode(const void* data, int size, Msg* message) {
  if (data == nullptr || size < 0 ||
      !PlausibleEncoding(static_cast<const Msg*>(nullptr), data, size)) {
    return false;
  }
  try {
    Msg decoded{};
    if (decoded.decode(data, 0, size) != size) return false;
    *message = std::move(decoded);
    return true;
  } catch (...) {  // std::length_error, std::bad_alloc: bad input is a false, never a throw
    return false;
  }
}

// Where a stage's outputs go: LCM in a live process, the output log in replay.
class MessageSink {
 public:
  virtual ~MessageSink() = default;
  virtual void Publish(const std::string& channel, const void* data, int size) = 0;

  template <class Msg>
  void PublishMessage(const std::string& channel, const Msg& message) {
    const std::vector<uint8_t> bytes = Encode(message);
    Publish(channel, bytes.data(), static_cast<int>(bytes.size()));
  }
};

// Writes an LCM event log (lcm-logger's format, playable by lcm-logplayer) as an OutputFile
// (runtime/output_file.h): the log appears under `path` only when Commit() succeeds; until
// then it is an unnamed file in the same directory (or an exclusively created
// "<path>.partial.<pid>.<n>"), never written through a link, and destroying an uncommitted
// writer leaves nothing behind (nor does killing the process, where the file system has
// O_TMPFILE).
//
// Format (LCM documentation, "LCM Log File Format"; what lcm_eventlog_write_event writes): per
// event, big-endian, the sync word 0xEDA1DA01, int64 event number (0, 1, 2, ... in file order),
// int64 timestamp [us], int32 channel length, int32 data length, then the channel name without
// its NUL and the data. The bytes are those lcm::LogFile would write (tested).
class LogWriter : public MessageSink {
 public:
  // Throws std::runtime_error when the file cannot be created.
  explicit LogWriter(const std::string& path);
  ~LogWriter() override;
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  // Event timestamps are the caller's (message time, never the wall clock), so the same input
  // gives the same bytes. Publish() uses the timestamp set by SetTimestamp().
  void Write(int64_t timestamp_us, const std::string& channel, const void* data, int size);
  void SetTimestamp(int64_t timestamp_us) { timestamp_us_ = timestamp_us; }
  void Publish(const std::string& channel, const void* data, int size) override;

  template <class Msg>
  void WriteMessage(int64_t timestamp_us, const std::string& channel, const Msg& message) {
    const std::vector<uint8_t> bytes = Encode(message);
    Write(timestamp_us, channel, bytes.data(), static_cast<int>(bytes.size()));
  }

  // Flushes, closes and moves the log into place. Throws on an I/O error.
  void Commit();
  int64_t events_written() const { return events_written_; }
  const std::string& path() const { return path_; }
  // The unfinished log's name on disk ("" when it has none), for tests.
  const std::string& partial_path() const { return file_->partial_path(); }

 private:
  std::string path_;
  std::unique_ptr<OutputFile> file_;
  int64_t timestamp_us_ = 0;
  int64_t events_written_ = 0;
  bool committed_ = false;
};

}  // namespace slammtt
