#include "runtime/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace slammtt {
namespace {

std::mutex& LogMutex() {
  static std::mutex mutex;
  return mutex;
}

std::string& ProgramName() {
  static std::string name = "slammtt";
  return name;
}

std::atomic<int>& Threshold() {
  static std::atomic<int> threshold{static_cast<int>(LogLevel::kInfo)};
  return threshold;
}

const char* LevelWord(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return "debug";
    case LogLevel::kInfo:
      return "info";
    case LogLevel::kWarning:
      return "warning";
    case LogLevel::kError:
      return "error";
  }
  return "?";
}

}  // namespace

void SetLogProgramName(const std::string& name) {
  std::lock_guard<std::mutex> lock(LogMutex());
  ProgramName() = name;
}

void SetLogLevel(LogLevel level) { Threshold() = static_cast<int>(level); }

LogLevel GetLogLevel() { return static_cast<LogLevel>(Threshold().load()); }

void LogLine(LogLevel level, const std::string& message) {
  if (static_cast<int>(level) < Threshold().load()) return;
  std::string one_line = message;
  for (char& c : one_line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::lock_guard<std::mutex> lock(LogMutex());
  std::fprintf(stderr, "%s: %s: %s\n", ProgramName().c_str(), LevelWord(level), one_line.c_str());
  std::fflush(stderr);
}

}  // namespace slammtt
