// Helpers of the tools tests: writing and reading small logs. Temporary directories (TempDir),
// programs and shell commands (RunCommand, Shell) come from tests/support/child_process.h.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "tests/support/child_process.h"

namespace slammtt::testing {

inline std::vector<uint8_t> Bytes(const std::string& text) {
  return std::vector<uint8_t>(text.begin(), text.end());
}

inline void WriteLog(const std::string& path, const std::vector<LogEvent>& events) {
  LogWriter writer(path);
  for (const LogEvent& e : events) {
    writer.Write(e.timestamp_us, e.channel, e.data.data(), static_cast<int>(e.data.size()));
  }
  writer.Commit();
}

inline std::vector<LogEvent> ReadLog(const std::string& path) {
  LogReader reader(path);
  std::vector<LogEvent> events;
  while (auto e = reader.Next()) events.push_back(std::move(*e));
  return events;
}

inline std::string FileBytes(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw std::runtime_error(path + ": cannot read");
  std::string bytes;
  char buffer[65536];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) bytes.append(buffer, n);
  std::fclose(f);
  return bytes;
}

inline void WriteFileBytes(const std::string& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error(path + ": cannot write");
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error(path + ": write failed");
}

inline bool FileExists(const std::string& path) { return access(path.c_str(), F_OK) == 0; }

// Every message of a log, by channel, in log order (empty when there is no file yet).
inline std::map<std::string, std::vector<std::string>> MessagesByChannel(
    const std::string& path) {
  std::map<std::string, std::vector<std::string>> out;
  if (!FileExists(path)) return out;
  for (const LogEvent& e : ReadLog(path)) {
    out[e.channel].emplace_back(e.data.begin(), e.data.end());
  }
  return out;
}

// Polls `condition` every 20 ms for at most `timeout_s`: synchronisation with other processes,
// never a measurement.
template <class Condition>
bool WaitFor(Condition condition, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000));
  while (std::chrono::steady_clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return condition();
}

}  // namespace slammtt::testing
