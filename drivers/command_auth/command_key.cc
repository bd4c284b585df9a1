#include "drivers/command_auth/command_key.h"

#include <fcntl.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace slammtt {
namespace {

// A key file holds 64 digits and perhaps a newline or a comment-free trailing blank: anything
// much longer is not a key file (and is not read into memory whole: /dev/zero, a log).
constexpr size_t kMaxKeyFileBytes = 4096;

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string Errno(const std::string& path, const std::string& what) {
  return path + ": " + what + ": " + std::strerror(errno);
}

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::optional<CommandKey> ParseCommandKey(const std::string& text) {
  size_t begin = 0;
  size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin])) != 0) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1])) != 0) --end;
  if (end - begin != 2 * kCommandKeyBytes) return std::nullopt;
  CommandKey key{};
  for (size_t k = 0; k < kCommandKeyBytes; ++k) {
    const int high = HexDigit(text[begin + 2 * k]);
    const int low = HexDigit(text[begin + 2 * k + 1]);
    if (high < 0 || low < 0) return std::nullopt;
    key[k] = static_cast<uint8_t>(high * 16 + low);
  }
  return key;
}

std::string CommandKeyText(const CommandKey& key) {
  static const char kDigits[] = "0123456789abcdef";
  std::string text;
  for (uint8_t byte : key) {
    text += kDigits[byte >> 4];
    text += kDigits[byte & 0x0F];
  }
  return text;
}

CommandKey LoadCommandKeyFile(const std::string& path) {
  // O_NONBLOCK: opening a FIFO planted under the key's name must not hang the driver.
  const Descriptor fd(open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (fd.get() < 0) throw std::runtime_error(Errno(path, "cannot open the command key file"));
  struct stat info {};
  if (fstat(fd.get(), &info) != 0) throw std::runtime_error(Errno(path, "cannot stat"));
  if (!S_ISREG(info.st_mode)) {
    throw std::runtime_error(path + ": the command key file is not a regular file");
  }
  if ((info.st_mode & 0007) != 0) {
    throw std::runtime_error(path + ": the command key file is open to other users (mode " +
                             std::to_string((info.st_mode >> 6) & 7) +
                             std::to_string((info.st_mode >> 3) & 7) +
                             std::to_string(info.st_mode & 7) + "); chmod o-rwx it");
  }
  if (info.st_size > static_cast<off_t>(kMaxKeyFileBytes)) {
    throw std::runtime_error(path + ": not a command key file (" + std::to_string(info.st_size) +
                             " bytes; a key is 64 hexadecimal digits)");
  }
  std::string text(kMaxKeyFileBytes + 1, '\0');
  size_t used = 0;
  for (;;) {
    const ssize_t n = read(fd.get(), text.data() + used, text.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(Errno(path, "cannot read the command key file"));
    if (n == 0) break;
    used += static_cast<size_t>(n);
    if (used > kMaxKeyFileBytes) {
      throw std::runtime_error(path + ": not a command key file (longer than " +
                               std::to_string(kMaxKeyFileBytes) + " bytes)");
    }
  }
  text.resize(used);
  const std::optional<CommandKey> key = ParseCommandKey(text);
  if (!key) {
    throw std::runtime_error(path +
                             ": not a command key file (expected 64 hexadecimal digits; "
                             "slammtt-command-key new FILE makes one)");
  }
  return *key;
}

CommandKey NewCommandKey() {
  CommandKey key{};
  if (RAND_bytes(key.data(), static_cast<int>(key.size())) != 1) {
    throw std::runtime_error("the random source failed (OpenSSL RAND_bytes)");
  }
  return key;
}

void WriteNewCommandKeyFile(const std::string& path, const CommandKey& key) {
  const Descriptor fd(
      open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
  if (fd.get() < 0) throw std::runtime_error(Errno(path, "cannot create the command key file"));
  const std::string text = CommandKeyText(key) + "\n";
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd.get(), text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string error = Errno(path, "cannot write the command key file");
      unlink(path.c_str());
      throw std::runtime_error(error);
    }
    done += static_cast<size_t>(n);
  }
  if (fsync(fd.get()) != 0) {
    const std::string error = Errno(path, "cannot write the command key file");
    unlink(path.c_str());
    throw std::runtime_error(error);
  }
}

}  // namespace slammtt
