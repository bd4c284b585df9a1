// A serial port opened through libserialport (8N1, no flow control), as a ByteStream.
//
// libserialport configures the port (baud rate, raw mode, DTR); the waits are poll() on the
// port's descriptor (sp_get_port_handle), because libserialport's blocking read cannot tell a
// hung-up port from a quiet one: after a hangup read() returns 0 at once, which
// sp_blocking_read() takes for "no data yet" and spins until its timeout. Here a hangup, an
// I/O error (USB adapter unplugged) or end of file is a LinkError. HUPCL is cleared, so closing
// the port leaves DTR and RTS as the driver set them (an RPLIDAR A2's motor stays off).
#pragma once

#include <memory>
#include <string>

#include "drivers/common/byte_stream.h"

struct sp_port;

namespace slammtt {

class SerialPortStream : public ByteStream {
 public:
  // Opens `device_path` at `baud` (any rate the driver accepts; libserialport 0.1.1 sets
  // non-standard rates such as 256000 through termios2 on Linux). A symlink such as
  // /dev/serial/by-id/... or a udev alias like /dev/rplidar is resolved first, because
  // libserialport looks the port up by its /dev name in /sys/class/tty. Throws LinkError with
  // the reason: no such device, permission denied (group dialout), not a serial port.
  static std::unique_ptr<SerialPortStream> Open(const std::string& device_path, int baud);
  ~SerialPortStream() override;
  SerialPortStream(const SerialPortStream&) = delete;
  SerialPortStream& operator=(const SerialPortStream&) = delete;

  void Write(const uint8_t* data, size_t size, int timeout_ms = 1000) override;
  // Returns 0 early when a signal interrupts the wait (loops then check for shutdown).
  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override;
  void FlushInput() override;
  void SetDtr(bool asserted) override;
  // "serial:/dev/ttyUSB0@115200", or "serial:/dev/rplidar=/dev/ttyUSB0@115200" for an alias.
  std::string Describe() const override { return description_; }
  // The port's descriptor (sp_get_port_handle): libserialport 0.1.1 buffers nothing of its
  // own, so the descriptor is readable exactly when Read() has data, and a hangup or an I/O
  // error of an unplugged adapter wakes poll() too.
  int PollDescriptor() const override { return fd_; }

 private:
  SerialPortStream(sp_port* port, std::string description);
  [[noreturn]] void Fail(const std::string& what) const;

  sp_port* port_;
  int fd_;
  std::string description_;
};

}  // namespace slammtt
