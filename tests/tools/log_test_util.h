// Helpers of the tools tests: writing and reading small logs. Temporary directories (TempDir),
// programs and shell commands (RunCommand, Shell) come from tests/support/child_process.h.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"
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

}  // namespace slammtt::testing
