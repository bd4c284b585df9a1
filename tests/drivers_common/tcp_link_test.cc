#include "drivers/common/tcp_link.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace slammtt {
namespace {

TEST(TcpEndpointTest, ParsesHostAndPort) {
  const TcpEndpoint endpoint = ParseTcpEndpoint("tcp://robot.local:4001");
  EXPECT_EQ(endpoint.host, "robot.local");
  EXPECT_EQ(endpoint.port, 4001);
  const TcpEndpoint v6 = ParseTcpEndpoint("tcp://[::1]:20108");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 20108);
}

TEST(TcpEndpointTest, RejectsMalformedEndpoints) {
  for (const char* bad : {"tcp://", "tcp://host", "tcp://host:", "tcp://:80", "tcp://h:0",
                          "tcp://h:65536", "tcp://h:12a", "tcp://a:b:1", "tcp://[::1]80",
                          "udp://h:1", "/dev/ttyUSB0"}) {
    EXPECT_THROW(ParseTcpEndpoint(bad), std::invalid_argument) << bad;
  }
}

std::unique_ptr<FdByteStream> AcceptSoon(TcpDeviceServer& server) {
  for (int i = 0; i < 100; ++i) {
    auto client = server.Accept(50);
    if (client) return client;
  }
  return nullptr;
}

TEST(TcpLinkTest, ClientAndDeviceServerExchangeBytes) {
  TcpDeviceServer server("127.0.0.1", 0);
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.Endpoint(), "tcp://127.0.0.1:" + std::to_string(server.port()));
  auto host = ConnectTcp(ParseTcpEndpoint(server.Endpoint()), 1000);
  auto device = AcceptSoon(server);
  ASSERT_TRUE(device);
  const uint8_t request[2] = {0xA5, 0x50};
  host->Write(request, 2);
  uint8_t buffer[4] = {};
  size_t got = 0;
  for (int i = 0; i < 50 && got < 2; ++i) got += device->Read(buffer + got, 2 - got, 50);
  EXPECT_EQ(got, 2u);
  EXPECT_EQ(buffer[0], 0xA5);
  EXPECT_EQ(buffer[1], 0x50);
}

TEST(TcpLinkTest, DeviceDroppingTheClientIsALinkErrorOnTheHost) {
  TcpDeviceServer server("127.0.0.1", 0);
  auto host = ConnectTcp(ParseTcpEndpoint(server.Endpoint()), 1000);
  auto device = AcceptSoon(server);
  ASSERT_TRUE(device);
  device.reset();
  uint8_t buffer[4];
  EXPECT_THROW(host->Read(buffer, sizeof buffer, 1000), LinkError);
}

TEST(TcpLinkTest, StoppedServerRefusesAndListensAgainOnTheSamePort) {
  TcpDeviceServer server("127.0.0.1", 0);
  const int port = server.port();
  server.StopListening();
  EXPECT_FALSE(server.listening());
  EXPECT_EQ(server.Accept(10), nullptr);
  try {
    ConnectTcp(ParseTcpEndpoint(server.Endpoint()), 1000);
    FAIL() << "connected to a server that does not listen";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("refused"), std::string::npos) << e.what();
  }
  server.Listen();
  EXPECT_EQ(server.port(), port);
  auto host = ConnectTcp(ParseTcpEndpoint(server.Endpoint()), 1000);
  EXPECT_TRUE(AcceptSoon(server));
}

TEST(TcpLinkTest, UnresolvableHostIsALinkError) {
  EXPECT_THROW(ConnectTcp(TcpEndpoint{"no-such-host.invalid", 1}, 500), LinkError);
}

}  // namespace
}  // namespace slammtt
