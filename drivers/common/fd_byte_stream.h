// A ByteStream over a POSIX file descriptor: a TCP socket (client or the device side of an
// emulator) or the master side of a pseudo-terminal. Every wait is a poll() bounded by the
// caller's timeout, so no call can hang; a peer that closed, hung up or failed is a LinkError.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "drivers/common/byte_stream.h"

namespace slammtt {

class FdByteStream : public ByteStream {
 public:
  // Takes ownership of `fd` and makes it non-blocking. `description` names the endpoint in
  // messages ("tcp://127.0.0.1:5000", "pty:/dev/pts/3").
  FdByteStream(int fd, std::string description);
  ~FdByteStream() override;
  FdByteStream(const FdByteStream&) = delete;
  FdByteStream& operator=(const FdByteStream&) = delete;

  // Contract of ByteStream. Read() returns 0 early when a signal interrupts the wait, so a loop
  // sees a shutdown request at once; end of stream (peer closed, pty hung up) is a LinkError.
  void Write(const uint8_t* data, size_t size, int timeout_ms = 1000) override;
  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override;
  // Reads and drops whatever is there now.
  void FlushInput() override;
  // No modem lines on a socket or a pty master.
  void SetDtr(bool asserted) override;
  std::string Describe() const override { return description_; }
  // The socket or pty master itself: Read() only ever returns what poll() reported.
  int PollDescriptor() const override { return fd_; }

  // For device emulators: writes what the peer's buffer accepts right now and returns how many
  // bytes that was, never waiting. A device's UART transmits whether or not the host reads, so
  // an emulator drops the rest (and counts it) instead of blocking its command handling.
  size_t WriteAvailable(const uint8_t* data, size_t size);

  int fd() const { return fd_; }

 private:
  [[noreturn]] void Fail(const std::string& what, int error_number) const;
  ssize_t WriteOnce(const uint8_t* data, size_t size);

  int fd_;
  bool is_socket_;
  std::string description_;
};

}  // namespace slammtt
