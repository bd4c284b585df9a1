// The device side of an emulated serial port: a Linux pseudo-terminal whose master end the
// emulator reads and writes, and whose slave end (/dev/pts/N) a driver opens as if it were the
// USB adapter of the real device. A driver opens it through libserialport only under
// tests/support/pty/pty-run (docs/drivers.md explains why); other programs (minicom, the
// Slamtec SDK's tools) open it as it is.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "drivers/common/fd_byte_stream.h"

namespace slammtt {

class PtyDevice {
 public:
  // Creates the pair in raw 8-bit mode (no echo, no line editing, no CR/LF translation) before
  // anyone opens the slave, so not one byte is altered. Throws LinkError when the system has
  // no pseudo-terminal left.
  PtyDevice();
  // Removes the published link (if it still names this device), then closes both ends: a host
  // that still has the slave open sees a hangup (poll POLLHUP, read 0), as when a USB adapter
  // is pulled and udev removes its /dev/... name.
  ~PtyDevice();
  PtyDevice(const PtyDevice&) = delete;
  PtyDevice& operator=(const PtyDevice&) = delete;

  // The path a host opens: "/dev/pts/N".
  const std::string& slave_path() const { return slave_path_; }
  // The emulator's end of the link.
  FdByteStream& stream() { return *master_; }

  // The DTR line the host set on the slave, when it can be observed: under pty-run the modem
  // line shim records it in $SLAMMTT_PTY_STATE_DIR/pts-N (DTR is asserted until the host
  // clears it, as on a real port after open()). nullopt when nothing records modem lines.
  std::optional<bool> HostDtr() const;

  // Makes `link_path` a symlink to slave_path(), replaced atomically, so that scripts and
  // drivers can use one stable name while the emulator re-creates its pty (a simulated unplug
  // gives a new /dev/pts/N). The link lives as long as this device: the destructor removes it
  // before the pty is closed, so no host retrying the name can ever open a /dev/pts/N that the
  // kernel has handed to someone else meanwhile (another test's emulator: pty numbers are
  // shared by the whole machine). Throws LinkError when the link cannot be written.
  void PublishLink(const std::string& link_path);

 private:
  std::unique_ptr<FdByteStream> master_;
  int held_slave_fd_ = -1;
  std::string slave_path_;
  std::string published_link_;  // "" when none
};

}  // namespace slammtt
