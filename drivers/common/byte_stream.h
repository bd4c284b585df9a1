// A byte link to a device, whatever carries it: a serial port opened through libserialport, or
// a TCP connection to a serial-to-network bridge (ser2net and the like). Both drivers and both
// emulators speak through this interface, so the tests exercise the same code path as the robot.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace slammtt {

// The link is unusable (device unplugged, peer closed, I/O error). what() is one line that names
// the endpoint. Drivers catch it, report it and reopen with backoff.
class LinkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ByteStream {
 public:
  virtual ~ByteStream() = default;
  // Writes every byte (waiting at most `timeout_ms` in all) or throws LinkError.
  virtual void Write(const uint8_t* data, size_t size, int timeout_ms = 1000) = 0;
  // Reads what is available, up to `capacity` bytes, waiting at most `timeout_ms` for the first
  // byte. Returns the number read, 0 on timeout. Throws LinkError when the link is gone.
  virtual size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) = 0;
  // Discards bytes received but not yet read.
  virtual void FlushInput() = 0;
  // Sets the DTR line where there is one (RPLIDAR A1/A2 motor enable); no-op over TCP.
  virtual void SetDtr(bool asserted) = 0;
  // "serial:/dev/ttyUSB0@115200" or "tcp://host:port", for messages and status.
  virtual std::string Describe() const = 0;
  // A descriptor that polls readable (POLLIN, or POLLHUP/POLLERR) whenever Read() would return
  // data or fail at once, so an owner can wait on the link together with its other inputs (the
  // LCM bus, ShutdownFd()) in one poll() and then call Read() with a timeout of 0. -1 when the
  // link has none (a test double): the owner then waits in Read() with a short timeout instead.
  // Valid until the stream is destroyed; never read it directly.
  virtual int PollDescriptor() const { return -1; }
};

// Checks the form of an endpoint without opening it: "tcp://HOST:PORT" with a port 1..65535,
// or an absolute serial port path (optionally "serial:/dev/..."), with a positive baud rate.
// Throws std::invalid_argument with a one-line reason: drivers call it on their configuration
// at start-up, so a typo fails at once instead of being retried forever as a link failure.
void CheckEndpoint(const std::string& endpoint, int baud);

// Opens an endpoint: "tcp://HOST:PORT" connects over TCP; anything else is a serial port path
// (optionally prefixed "serial:"; symlinks such as /dev/serial/by-id/... are resolved) opened
// with libserialport at `baud`, 8N1, no flow control. Throws LinkError on failure with
// the reason (no such device, permission denied, connection refused).
std::unique_ptr<ByteStream> OpenByteStream(const std::string& endpoint, int baud,
                                           int connect_timeout_ms = 2000);

}  // namespace slammtt
