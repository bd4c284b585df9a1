#include "drivers/common/pty_device.h"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace slammtt {
namespace {

[[noreturn]] void FailErrno(const std::string& what) {
  throw LinkError("pty: " + what + ": " + std::strerror(errno));
}

void MakeRaw(int fd) {
  struct termios settings = {};
  if (tcgetattr(fd, &settings) != 0) FailErrno("tcgetattr");
  cfmakeraw(&settings);
  settings.c_cflag |= CLOCAL | CREAD;
  if (tcsetattr(fd, TCSANOW, &settings) != 0) FailErrno("tcsetattr");
}

}  // namespace

PtyDevice::PtyDevice() {
  const int master_fd = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master_fd < 0) FailErrno("posix_openpt");
  // From here the master belongs to master_, so an error below cannot leak it.
  char name[128];
  if (grantpt(master_fd) != 0 || unlockpt(master_fd) != 0 ||
      ptsname_r(master_fd, name, sizeof name) != 0) {
    const int error = errno;
    close(master_fd);
    errno = error;
    FailErrno("cannot unlock the slave");
  }
  slave_path_ = name;
  master_ = std::make_unique<FdByteStream>(master_fd, "pty:" + slave_path_ + " (device side)");
  // Holding a slave descriptor keeps the line up while the host closes and reopens the port
  // (without it, the master reads EIO between two host sessions), like a UART that stays
  // powered whether or not a host is attached.
  held_slave_fd_ = open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (held_slave_fd_ < 0) FailErrno("cannot open " + slave_path_);
  MakeRaw(held_slave_fd_);
}

PtyDevice::~PtyDevice() {
  if (!published_link_.empty()) {
    // Only our own link: a newer device may have taken the name over.
    char target[PATH_MAX];
    const ssize_t length = readlink(published_link_.c_str(), target, sizeof target - 1);
    if (length > 0 && std::string(target, static_cast<size_t>(length)) == slave_path_) {
      unlink(published_link_.c_str());
    }
  }
  master_.reset();
  if (held_slave_fd_ >= 0) close(held_slave_fd_);
}

std::optional<bool> PtyDevice::HostDtr() const {
  const char* state_dir = std::getenv("SLAMMTT_PTY_STATE_DIR");
  if (state_dir == nullptr || state_dir[0] == '\0') return std::nullopt;
  const std::string prefix = "/dev/pts/";
  if (slave_path_.rfind(prefix, 0) != 0) return std::nullopt;
  std::ifstream file(std::string(state_dir) + "/pts-" + slave_path_.substr(prefix.size()));
  int lines = 0;
  if (!(file >> lines)) return true;  // never set: asserted, as after open()
  return (lines & TIOCM_DTR) != 0;
}

void PtyDevice::PublishLink(const std::string& link_path) {
  const std::string temporary = link_path + ".new";
  unlink(temporary.c_str());
  if (symlink(slave_path_.c_str(), temporary.c_str()) != 0) {
    FailErrno("cannot create the link " + temporary);
  }
  if (rename(temporary.c_str(), link_path.c_str()) != 0) {
    const int error = errno;
    unlink(temporary.c_str());
    errno = error;
    FailErrno("cannot replace " + link_path);
  }
  published_link_ = link_path;
}

}  // namespace slammtt
