// libserialport opens a pseudo-terminal under tests/support/pty/pty-run: the path every driver
// test takes to reach its emulator as it would reach the device on the robot.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <memory>
#include <numeric>
#include <vector>

#include "drivers/common/byte_stream.h"
#include "drivers/common/pty_device.h"
#include "byte_stream_test_util.h"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

class SerialPtyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(getenv("SLAMMTT_IN_PTY_NS"), nullptr)
        << "run this program under tests/support/pty/pty-run (ctest does)";
  }
};

TEST_F(SerialPtyTest, LibserialportOpensThePtyAndCarriesEveryByte) {
  PtyDevice device;
  auto host = OpenByteStream(device.slave_path(), 115200);
  EXPECT_EQ(host->Describe(), "serial:" + device.slave_path() + "@115200");
  std::vector<uint8_t> all(256);
  std::iota(all.begin(), all.end(), 0);
  host->Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(device.stream(), 256), all);
  device.stream().Write(all.data(), all.size());
  EXPECT_EQ(ReadExactly(*host, 256), all);
}

TEST_F(SerialPtyTest, PollDescriptorWakesForBytesAndForAnUnpluggedDevice) {
  auto device = std::make_unique<PtyDevice>();
  auto host = OpenByteStream(device->slave_path(), 9600);
  const int fd = host->PollDescriptor();
  ASSERT_GE(fd, 0);
  EXPECT_FALSE(PollsReady(fd, 0));
  const uint8_t bytes[3] = {0xFA, 0xFB, 0x03};
  device->stream().Write(bytes, 3);
  ASSERT_TRUE(PollsReady(fd, 1000));
  EXPECT_EQ(ReadExactly(*host, 3), std::vector<uint8_t>({0xFA, 0xFB, 0x03}));
  EXPECT_FALSE(PollsReady(fd, 0));
  device.reset();  // the "USB adapter" is pulled: the wait ends, and Read() fails at once
  ASSERT_TRUE(PollsReady(fd, 1000));
  uint8_t buffer[8];
  EXPECT_THROW(host->Read(buffer, sizeof buffer, 0), LinkError);
}

TEST_F(SerialPtyTest, DeviceSideSeesTheDtrLineTheHostSets) {
  PtyDevice device;
  auto host = OpenByteStream(device.slave_path(), 115200);
  ASSERT_TRUE(device.HostDtr().has_value());
  EXPECT_TRUE(*device.HostDtr());  // asserted after open, as on a real port
  host->SetDtr(false);
  EXPECT_FALSE(*device.HostDtr());
  host->SetDtr(true);
  EXPECT_TRUE(*device.HostDtr());
}

TEST_F(SerialPtyTest, ClosingThePortLeavesTheModemLinesAlone) {
  PtyDevice device;
  {
    auto host = OpenByteStream(device.slave_path(), 115200);
    // libserialport sets HUPCL on open; SerialPortStream clears it.
    struct termios settings = {};
    const int fd = open(device.slave_path().c_str(), O_RDWR | O_NOCTTY);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(tcgetattr(fd, &settings), 0);
    close(fd);
    EXPECT_EQ(settings.c_cflag & HUPCL, 0u);
  }
}

TEST_F(SerialPtyTest, NonStandardAndLowBaudRatesAreAccepted) {
  PtyDevice device;
  for (int baud : {9600, 115200, 256000}) {
    auto host = OpenByteStream(device.slave_path(), baud);
    EXPECT_EQ(host->Describe(), "serial:" + device.slave_path() + "@" + std::to_string(baud));
  }
}

TEST_F(SerialPtyTest, UnpluggedDeviceIsALinkErrorAndTheLinkNameFindsTheNewOne) {
  const testing::TempDir directory("slammtt-serial-pty");
  const std::string link = directory.File("lidar");

  auto device = std::make_unique<PtyDevice>();
  device->PublishLink(link);
  auto host = OpenByteStream(link, 115200);
  EXPECT_EQ(host->Describe(), "serial:" + link + "=" + device->slave_path() + "@115200");
  device.reset();  // the "USB adapter" is pulled
  uint8_t buffer[8];
  try {
    host->Read(buffer, sizeof buffer, 1000);
    FAIL() << "no LinkError after the device went away";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find(link), std::string::npos) << e.what();
  }
  host.reset();

  device = std::make_unique<PtyDevice>();  // plugged in again: a new /dev/pts/N
  device->PublishLink(link);
  host = OpenByteStream(link, 115200);
  const uint8_t byte = 0x5A;
  device->stream().Write(&byte, 1);
  EXPECT_EQ(ReadExactly(*host, 1), std::vector<uint8_t>({0x5A}));
}

}  // namespace
}  // namespace slammtt
