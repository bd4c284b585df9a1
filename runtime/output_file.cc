#include "runtime/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace slammtt {
namespace {

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string ProcPath(int fd) { return "/proc/self/fd/" + std::to_string(fd); }

[[noreturn]] void Fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(errno));
}

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path) {
  if (path.empty()) throw std::runtime_error("output file: empty path");
  int fd = open(DirectoryOf(path).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0 && access(ProcPath(fd).c_str(), F_OK) != 0) {
    close(fd);  // no /proc to name it by: a named partial file instead
    fd = -1;
  }
  if (fd < 0) {
    for (int n = 0; fd < 0; ++n) {
      partial_path_ = path + ".partial." + std::to_string(getpid()) + "." + std::to_string(n);
      fd = open(partial_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
      if (fd < 0 && (errno != EEXIST || n >= 1000)) {
        partial_path_.clear();
        Fail(path, "cannot create the output file");
      }
    }
  }
  stream_ = fdopen(fd, "wb");
  if (stream_ == nullptr) {
    const int saved = errno;
    close(fd);
    if (!partial_path_.empty()) unlink(partial_path_.c_str());
    errno = saved;
    Fail(path, "cannot create the output file");
  }
}

OutputFile::~OutputFile() {
  if (!committed_) Discard();
}

void OutputFile::Discard() {
  if (stream_ != nullptr) std::fclose(stream_);
  stream_ = nullptr;
  if (!partial_path_.empty()) unlink(partial_path_.c_str());
}

void OutputFile::Commit() {
  if (committed_) return;
  if (stream_ == nullptr) throw std::runtime_error(path_ + ": output file already discarded");
  const int fd = fileno(stream_);
  if (std::fflush(stream_) != 0 || std::ferror(stream_) != 0 || fsync(fd) != 0) {
    Discard();
    throw std::runtime_error(path_ + ": write failed (disk full?)");
  }
  std::string named = partial_path_;
  if (named.empty()) {
    // Give the unnamed file a name no one else has, beside the target, then rename that.
    for (int n = 0;; ++n) {
      named = path_ + ".partial." + std::to_string(getpid()) + "." + std::to_string(n);
      if (linkat(AT_FDCWD, ProcPath(fd).c_str(), AT_FDCWD, named.c_str(), AT_SYMLINK_FOLLOW) ==
          0) {
        break;
      }
      if (errno != EEXIST || n >= 1000) {
        const int saved = errno;
        Discard();
        errno = saved;
        Fail(path_, "cannot name the finished file");
      }
    }
  }
  if (std::rename(named.c_str(), path_.c_str()) != 0) {
    const int saved = errno;
    unlink(named.c_str());
    partial_path_.clear();
    Discard();
    errno = saved;
    Fail(path_, "cannot move the finished file into place");
  }
  partial_path_.clear();
  const bool closed = std::fclose(stream_) == 0;
  stream_ = nullptr;
  committed_ = true;
  if (!closed) throw std::runtime_error(path_ + ": write failed while closing");
}

}  // namespace slammtt
