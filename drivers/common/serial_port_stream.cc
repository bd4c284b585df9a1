#include "drivers/common/serial_port_stream.h"

#include <libserialport.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace slammtt {
namespace {

using SteadyClock = std::chrono::steady_clock;

std::string LastSerialError() {
  char* text = sp_last_error_message();
  std::string message = text != nullptr ? text : "unknown error";
  sp_free_error_message(text);
  return message;
}

// What libserialport's failure most likely means, for the one-line message a user reads.
std::string ExplainOpenFailure(const std::string& path, int error_number) {
  switch (error_number) {
    case EACCES:
    case EPERM:
      return "permission denied (add the user to the group that owns " + path +
             ", usually dialout)";
    case ENOENT:
    case ENODEV:
    case ENXIO:
      return "no such device (unplugged?)";
    case EBUSY:
      return "device busy";
    default:
      return LastSerialError();
  }
}

}  // namespace

std::unique_ptr<SerialPortStream> SerialPortStream::Open(const std::string& device_path,
                                                          int baud) {
  const std::string prefix = "serial:" + device_path + "@" + std::to_string(baud) + ": ";
  if (baud <= 0) throw LinkError(prefix + "baud rate must be positive");
  struct stat info = {};
  if (stat(device_path.c_str(), &info) != 0) {
    throw LinkError(prefix + "no such device (unplugged?)");
  }
  if (!S_ISCHR(info.st_mode)) throw LinkError(prefix + "not a character device");
  char resolved[PATH_MAX];
  std::string real_path = device_path;
  if (realpath(device_path.c_str(), resolved) != nullptr) real_path = resolved;

  sp_port* port = nullptr;
  if (sp_get_port_by_name(real_path.c_str(), &port) != SP_OK) {
    throw LinkError(prefix + real_path +
                    " is not a serial port known to /sys/class/tty (a pseudo-terminal needs "
                    "tests/support/pty/pty-run, see docs/drivers.md)");
  }
  errno = 0;
  if (sp_open(port, SP_MODE_READ_WRITE) != SP_OK) {
    const int error_number = errno;
    const std::string reason = ExplainOpenFailure(device_path, error_number);
    sp_free_port(port);
    throw LinkError(prefix + reason);
  }
  if (sp_set_baudrate(port, baud) != SP_OK || sp_set_bits(port, 8) != SP_OK ||
      sp_set_parity(port, SP_PARITY_NONE) != SP_OK || sp_set_stopbits(port, 1) != SP_OK ||
      sp_set_flowcontrol(port, SP_FLOWCONTROL_NONE) != SP_OK) {
    const std::string reason = LastSerialError();
    sp_close(port);
    sp_free_port(port);
    throw LinkError(prefix + "cannot configure 8N1 at this baud rate: " + reason);
  }
  // libserialport 0.1.1 sets HUPCL on open (serialport.c, sp_open), so the kernel drops DTR
  // and RTS when the port closes. On an RPLIDAR A1/A2 a dropped DTR starts the motor: the
  // driver's "motor off" would be undone the moment the process exits. Without HUPCL the lines
  // stay as the driver left them; the next open() raises them again anyway.
  int handle = -1;
  struct termios settings = {};
  if (sp_get_port_handle(port, &handle) != SP_OK || tcgetattr(handle, &settings) != 0) {
    sp_close(port);
    sp_free_port(port);
    throw LinkError(prefix + "cannot read the line settings");
  }
  settings.c_cflag &= ~static_cast<tcflag_t>(HUPCL);
  if (tcsetattr(handle, TCSANOW, &settings) != 0) {
    const int error_number = errno;
    sp_close(port);
    sp_free_port(port);
    throw LinkError(prefix + "cannot clear HUPCL: " + std::strerror(error_number));
  }
  std::string description = "serial:" + device_path;
  if (real_path != device_path) description += "=" + real_path;
  description += "@" + std::to_string(baud);
  return std::unique_ptr<SerialPortStream>(new SerialPortStream(port, description));
}

SerialPortStream::SerialPortStream(sp_port* port, std::string description)
    : port_(port), fd_(-1), description_(std::move(description)) {
  int handle = -1;
  if (sp_get_port_handle(port_, &handle) == SP_OK) fd_ = handle;
}

SerialPortStream::~SerialPortStream() {
  sp_close(port_);
  sp_free_port(port_);
}

void SerialPortStream::Fail(const std::string& what) const {
  throw LinkError(description_ + ": " + what);
}

void SerialPortStream::Write(const uint8_t* data, size_t size, int timeout_ms) {
  if (size == 0) return;
  const sp_return written =
      sp_blocking_write(port_, data, size, static_cast<unsigned int>(timeout_ms < 0 ? 0 : timeout_ms));
  if (written < 0) Fail("write failed: " + LastSerialError());
  if (static_cast<size_t>(written) < size) {
    Fail("write timed out after " + std::to_string(timeout_ms) + " ms (" +
         std::to_string(static_cast<int>(written)) + " of " + std::to_string(size) +
         " bytes sent)");
  }
}

size_t SerialPortStream::Read(uint8_t* buffer, size_t capacity, int timeout_ms) {
  if (capacity == 0) return 0;
  struct pollfd entry = {fd_, POLLIN, 0};
  const int ready = poll(&entry, 1, timeout_ms < 0 ? 0 : timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return 0;
    Fail(std::string("poll failed: ") + std::strerror(errno));
  }
  if (ready == 0) return 0;
  if ((entry.revents & POLLNVAL) != 0) Fail("port is not open");
  const sp_return got = sp_nonblocking_read(port_, buffer, capacity);
  if (got < 0) Fail("read failed (device unplugged?): " + LastSerialError());
  if (got > 0) return static_cast<size_t>(got);
  // Readable or hung up, yet nothing to read: the far end is gone (a tty after hangup reads 0).
  Fail("port hung up (device unplugged?)");
}

void SerialPortStream::FlushInput() {
  if (sp_flush(port_, SP_BUF_INPUT) != SP_OK) Fail("flush failed: " + LastSerialError());
}

void SerialPortStream::SetDtr(bool asserted) {
  if (sp_set_dtr(port_, asserted ? SP_DTR_ON : SP_DTR_OFF) != SP_OK) {
    Fail("cannot set DTR: " + LastSerialError());
  }
}

}  // namespace slammtt
