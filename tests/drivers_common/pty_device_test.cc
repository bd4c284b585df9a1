#include "drivers/common/pty_device.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <memory>
#include <numeric>
#include <vector>

#include "byte_stream_test_util.h"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

// The host side without libserialport: a plain open() of the slave, as minicom would.
std::unique_ptr<FdByteStream> OpenHost(const std::string& path) {
  const int fd = open(path.c_str(), O_RDWR | O_NOCTTY);
  if (fd < 0) return nullptr;
  return std::make_unique<FdByteStream>(fd, "host:" + path);
}

TEST(PtyDeviceTest, RawLinkCarriesEveryByteValueUnchanged) {
  PtyDevice device;
  EXPECT_EQ(device.slave_path().rfind("/dev/pts/", 0), 0u) << device.slave_path();
  auto host = OpenHost(device.slave_path());
  ASSERT_TRUE(host);
  // CR, LF, ^C, XON/XOFF, DEL and 0xFF are the bytes a cooked tty would alter or swallow.
  std::vector<uint8_t> all(256);
  std::iota(all.begin(), all.end(), 0);
  device.stream().Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(*host, 256), all);
  host->Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(device.stream(), 256), all);
  // No echo: the device side got exactly what the host sent, nothing more.
  uint8_t extra[4];
  EXPECT_EQ(device.stream().Read(extra, sizeof extra, 20), 0u);
  EXPECT_EQ(host->Read(extra, sizeof extra, 20), 0u);
}

TEST(PtyDeviceTest, HostMayCloseAndReopen) {
  PtyDevice device;
  auto host = OpenHost(device.slave_path());
  ASSERT_TRUE(host);
  host.reset();
  // The device side keeps working with no host attached.
  const uint8_t byte = 0x42;
  device.stream().Write(&byte, 1);
  uint8_t buffer[4];
  EXPECT_EQ(device.stream().Read(buffer, sizeof buffer, 10), 0u);
  host = OpenHost(device.slave_path());
  ASSERT_TRUE(host);
  host->FlushInput();
  device.stream().Write(&byte, 1);
  EXPECT_EQ(ReadExactly(*host, 1), std::vector<uint8_t>({0x42}));
}

TEST(PtyDeviceTest, DestroyingTheDeviceHangsUpTheHost) {
  auto device = std::make_unique<PtyDevice>();
  auto host = OpenHost(device->slave_path());
  ASSERT_TRUE(host);
  device.reset();
  uint8_t buffer[4];
  EXPECT_THROW(host->Read(buffer, sizeof buffer, 1000), LinkError);
}

TEST(PtyDeviceTest, PublishLinkPointsAStableNameAtTheCurrentPty) {
  const testing::TempDir directory("slammtt-pty-test");
  const std::string link = directory.File("lidar");
  std::string first_path;
  {
    PtyDevice first;
    first.PublishLink(link);
    first_path = first.slave_path();
    char resolved[PATH_MAX];
    ASSERT_NE(realpath(link.c_str(), resolved), nullptr);
    EXPECT_EQ(std::string(resolved), first.slave_path());
  }
  PtyDevice second;
  second.PublishLink(link);
  char target[PATH_MAX] = {};
  ASSERT_GT(readlink(link.c_str(), target, sizeof target - 1), 0);
  EXPECT_EQ(std::string(target), second.slave_path());
}

// Like udev removing /dev/rplidar when the adapter is pulled: a host retrying the name must
// never reach a /dev/pts/N that the kernel has meanwhile given to another program (pty numbers
// are shared by the whole machine; parallel tests once stole each other's bytes that way).
TEST(PtyDeviceTest, TheLinkGoesWithItsDeviceButNeverTakesANewerOneWithIt) {
  const testing::TempDir directory("slammtt-pty-test");
  const std::string link = directory.File("lidar");
  {
    PtyDevice device;
    device.PublishLink(link);
    ASSERT_EQ(access(link.c_str(), F_OK), 0);
  }
  struct stat info = {};
  EXPECT_NE(lstat(link.c_str(), &info), 0) << "the link outlived its device";

  auto older = std::make_unique<PtyDevice>();
  older->PublishLink(link);
  PtyDevice newer;
  newer.PublishLink(link);
  older.reset();
  char target[PATH_MAX] = {};
  ASSERT_GT(readlink(link.c_str(), target, sizeof target - 1), 0);
  EXPECT_EQ(std::string(target), newer.slave_path());
}

TEST(PtyDeviceTest, HostDtrIsUnknownWithoutTheShimState) {
  if (getenv("SLAMMTT_PTY_STATE_DIR") != nullptr) GTEST_SKIP() << "running under pty-run";
  PtyDevice device;
  EXPECT_FALSE(device.HostDtr().has_value());
}

}  // namespace
}  // namespace slammtt
