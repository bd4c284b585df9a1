// OpenByteStream and CheckEndpoint outside the pty namespace: the errors a user meets.
#include "drivers/common/byte_stream.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <stdexcept>

#include "drivers/common/pty_device.h"
#include "drivers/common/tcp_link.h"

namespace slammtt {
namespace {

std::string LinkErrorOf(const std::string& endpoint, int baud) {
  try {
    OpenByteStream(endpoint, baud, 500);
  } catch (const LinkError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckEndpointTest, AcceptsSerialPathsAndTcp) {
  EXPECT_NO_THROW(CheckEndpoint("/dev/ttyUSB0", 115200));
  EXPECT_NO_THROW(CheckEndpoint("serial:/dev/ttyUSB0", 256000));
  EXPECT_NO_THROW(CheckEndpoint("tcp://127.0.0.1:2000", 0));
}

TEST(CheckEndpointTest, RejectsTyposBeforeAnyOpen) {
  EXPECT_THROW(CheckEndpoint("", 115200), std::invalid_argument);
  EXPECT_THROW(CheckEndpoint("ttyUSB0", 115200), std::invalid_argument);
  EXPECT_THROW(CheckEndpoint("/dev/ttyUSB0", 0), std::invalid_argument);
  EXPECT_THROW(CheckEndpoint("tcp://host", 115200), std::invalid_argument);
}

TEST(OpenByteStreamTest, MissingDeviceSaysSo) {
  const std::string message = LinkErrorOf("/dev/ttyNOSUCHDEVICE7", 115200);
  EXPECT_NE(message.find("/dev/ttyNOSUCHDEVICE7"), std::string::npos) << message;
  EXPECT_NE(message.find("no such device"), std::string::npos) << message;
}

TEST(OpenByteStreamTest, NotACharacterDeviceSaysSo) {
  const std::string message = LinkErrorOf("/etc/hostname", 115200);
  EXPECT_NE(message.find("not a character device"), std::string::npos) << message;
}

TEST(OpenByteStreamTest, MalformedEndpointIsALinkErrorToo) {
  EXPECT_NE(LinkErrorOf("tcp://nowhere", 115200).find("tcp://HOST:PORT"), std::string::npos);
}

TEST(OpenByteStreamTest, PtyOutsidePtyRunPointsAtTheFix) {
  if (getenv("SLAMMTT_IN_PTY_NS") != nullptr) GTEST_SKIP() << "running under pty-run";
  PtyDevice device;
  const std::string message = LinkErrorOf(device.slave_path(), 115200);
  EXPECT_NE(message.find("pty-run"), std::string::npos) << message;
}

TEST(OpenByteStreamTest, TcpEndpointConnects) {
  TcpDeviceServer server("127.0.0.1", 0);
  auto stream = OpenByteStream(server.Endpoint(), 115200, 1000);
  ASSERT_TRUE(stream);
  EXPECT_EQ(stream->Describe(), server.Endpoint());
  stream->SetDtr(true);  // no modem lines over TCP: accepted and ignored
}

TEST(OpenByteStreamTest, RefusedTcpNamesTheEndpoint) {
  TcpDeviceServer server("127.0.0.1", 0);
  const std::string endpoint = server.Endpoint();
  server.StopListening();
  const std::string message = LinkErrorOf(endpoint, 115200);
  EXPECT_NE(message.find(endpoint), std::string::npos) << message;
}

}  // namespace
}  // namespace slammtt
