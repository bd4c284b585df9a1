// Helpers of the tools tests: temporary directories, writing and reading small logs.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/lcm_io.h"

namespace slammtt::testing {

// A fresh directory under $TMPDIR (or /tmp), removed with its contents at the end of the test.
class TempDir {
 public:
  TempDir() {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base != nullptr ? base : "/tmp") + "/slammtt-tools-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    const std::string command = "rm -rf '" + path_ + "'";
    if (std::system(command.c_str()) != 0) {
      // nothing to do: a leftover temporary directory is harmless
    }
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string File(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

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

// Runs `command` with /bin/sh and returns what it printed on stdout; *status gets pclose()'s
// status (0 when the command exited with 0).
inline std::string RunCommand(const std::string& command, int* status) {
  std::FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  if (pipe == nullptr) {
    *status = -1;
    return out;
  }
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.append(buffer, n);
  *status = pclose(pipe);
  return out;
}

// The same with stderr mixed into the output; returns the status.
inline int Shell(const std::string& command, std::string* output = nullptr) {
  int status = 0;
  const std::string out = RunCommand(command + " 2>&1", &status);
  if (output != nullptr) *output = out;
  return status;
}

}  // namespace slammtt::testing
