#include "runtime/lcm_io.h"

#include "runtime/lcm_url.h"
#include "runtime/log.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace slammtt {

std::string ResolveLcmUrl(const std::optional<std::string>& from_command_line,
                          const std::optional<std::string>& from_config) {
  if (from_command_line && !from_command_line->empty()) return *from_command_line;
  if (from_config && !from_config->empty()) return *from_config;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  if (env != nullptr && env[0] != '\0') return env;
  return kDefaultLcmUrl;
}

namespace {

// LCM 1.3.1 prints a dozen lines of its own to stderr when it cannot start (no multicast route,
// a bad URL). Our error says what is wrong and how to fix it in one line, so LCM's lines are
// kept off stderr while the bus is being opened. Every process opens its bus before it starts
// any thread, so redirecting the process's stderr for this moment disturbs nobody.
std::unique_ptr<lcm::LCM> ConstructQuietly(const std::string& url) {
  std::fflush(stderr);
  const int saved = dup(STDERR_FILENO);
  const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved >= 0 && null_fd >= 0) dup2(null_fd, STDERR_FILENO);
  auto lcm = std::make_unique<lcm::LCM>(url);
  std::fflush(stderr);
  if (saved >= 0) {
    dup2(saved, STDERR_FILENO);
    close(saved);
  }
  if (null_fd >= 0) close(null_fd);
  return lcm;
}

}  // namespace

std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url) {
  try {
    ParseLcmUrl(url);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  auto lcm = ConstructQuietly(url);
  if (!lcm->good()) {
    std::string message = "cannot open LCM at '" + url + "'";
    if (url.rfind("udpm://", 0) == 0) {
      message +=
          " (LCM needs a multicast route: 'ip route add 224.0.0.0/4 dev lo' on a host without "
          "a network, or a default route)";
    }
    throw std::runtime_error(message);
  }
  return lcm;
}

LogWriter::LogWriter(const std::string& path)
    : path_(path), file_(std::make_unique<OutputFile>(path)) {}

LogWriter::~LogWriter() = default;  // an uncommitted OutputFile discards itself

namespace {

bool WriteBigEndian(std::FILE* f, uint64_t value, int bytes) {
  uint8_t buffer[8];
  for (int k = 0; k < bytes; ++k) buffer[k] = static_cast<uint8_t>(value >> (8 * (bytes - 1 - k)));
  return std::fwrite(buffer, 1, static_cast<size_t>(bytes), f) == static_cast<size_t>(bytes);
}

constexpr uint32_t kLogSyncWord = 0xEDA1DA01u;

}  // namespace

void LogWriter::Write(int64_t timestamp_us, const std::string& channel, const void* data,
                      int size) {
  if (committed_) throw std::runtime_error(path_ + ": log already closed");
  if (size < 0) throw std::invalid_argument(path_ + ": negative event size");
  std::FILE* f = file_->stream();
  const bool ok = WriteBigEndian(f, kLogSyncWord, 4) &&
                  WriteBigEndian(f, static_cast<uint64_t>(events_written_), 8) &&
                  WriteBigEndian(f, static_cast<uint64_t>(timestamp_us), 8) &&
                  WriteBigEndian(f, static_cast<uint32_t>(channel.size()), 4) &&
                  WriteBigEndian(f, static_cast<uint32_t>(size), 4) &&
                  std::fwrite(channel.data(), 1, channel.size(), f) == channel.size() &&
                  std::fwrite(data, 1, static_cast<size_t>(size), f) == static_cast<size_t>(size);
  if (!ok) throw std::runtime_error(path_ + ": write failed");
  ++events_written_;
}

void LogWriter::Publish(const std::string& channel, const void* data, int size) {
  Write(timestamp_us_, channel, data, size);
}

void LogWriter::Commit() {
  if (committed_) return;
  file_->Commit();
  committed_ = true;
}

}  // namespace slammtt
