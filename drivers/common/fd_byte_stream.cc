#include "drivers/common/fd_byte_stream.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <utility>

namespace slammtt {
namespace {

using SteadyClock = std::chrono::steady_clock;

int RemainingMs(SteadyClock::time_point deadline) {
  const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

}  // namespace

FdByteStream::FdByteStream(int fd, std::string description)
    : fd_(fd), is_socket_(false), description_(std::move(description)) {
  struct stat info = {};
  if (fstat(fd_, &info) == 0) is_socket_ = S_ISSOCK(info.st_mode);
  const int flags = fcntl(fd_, F_GETFL);
  if (flags >= 0) fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  fcntl(fd_, F_SETFD, FD_CLOEXEC);
}

FdByteStream::~FdByteStream() {
  if (fd_ >= 0) close(fd_);
}

void FdByteStream::Fail(const std::string& what, int error_number) const {
  std::string message = description_ + ": " + what;
  if (error_number != 0) message += ": " + std::string(std::strerror(error_number));
  throw LinkError(message);
}

ssize_t FdByteStream::WriteOnce(const uint8_t* data, size_t size) {
  // MSG_NOSIGNAL: a closed TCP peer is an error return, not a SIGPIPE, even in programs that
  // did not ignore the signal.
  return is_socket_ ? send(fd_, data, size, MSG_NOSIGNAL) : write(fd_, data, size);
}

void FdByteStream::Write(const uint8_t* data, size_t size, int timeout_ms) {
  const auto deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
  size_t done = 0;
  while (done < size) {
    const ssize_t written = WriteOnce(data + done, size - done);
    if (written > 0) {
      done += static_cast<size_t>(written);
      continue;
    }
    if (written < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      Fail("write failed", errno);
    }
    const int left_ms = RemainingMs(deadline);
    if (left_ms == 0) {
      Fail("write timed out after " + std::to_string(timeout_ms) + " ms (" +
               std::to_string(done) + " of " + std::to_string(size) + " bytes sent)",
           0);
    }
    struct pollfd entry = {fd_, POLLOUT, 0};
    const int ready = poll(&entry, 1, left_ms);
    if (ready < 0 && errno != EINTR) Fail("poll failed", errno);
    if (ready > 0 && (entry.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 &&
        (entry.revents & POLLOUT) == 0) {
      Fail("link closed by the peer", 0);
    }
  }
}

size_t FdByteStream::WriteAvailable(const uint8_t* data, size_t size) {
  size_t done = 0;
  while (done < size) {
    const ssize_t written = WriteOnce(data + done, size - done);
    if (written > 0) {
      done += static_cast<size_t>(written);
      continue;
    }
    if (written < 0 && errno == EINTR) continue;
    if (written < 0 && errno != EAGAIN && errno != EWOULDBLOCK) Fail("write failed", errno);
    break;
  }
  return done;
}

size_t FdByteStream::Read(uint8_t* buffer, size_t capacity, int timeout_ms) {
  if (capacity == 0) return 0;
  struct pollfd entry = {fd_, POLLIN, 0};
  const int ready = poll(&entry, 1, timeout_ms < 0 ? 0 : timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return 0;
    Fail("poll failed", errno);
  }
  if (ready == 0) return 0;
  if ((entry.revents & POLLNVAL) != 0) Fail("descriptor is not open", 0);
  // Data that arrived before a hangup is still delivered; only then does the hangup count.
  const ssize_t got = read(fd_, buffer, capacity);
  if (got > 0) return static_cast<size_t>(got);
  if (got == 0) Fail("link closed by the peer", 0);
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
    if ((entry.revents & (POLLERR | POLLHUP)) != 0) Fail("link hung up", 0);
    return 0;
  }
  Fail("read failed", errno);
}

void FdByteStream::FlushInput() {
  uint8_t scratch[4096];
  for (;;) {
    const ssize_t got = read(fd_, scratch, sizeof scratch);
    if (got > 0) continue;
    if (got == 0) Fail("link closed by the peer", 0);
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return;
    Fail("read failed", errno);
  }
}

void FdByteStream::SetDtr(bool /*asserted*/) {}

}  // namespace slammtt
