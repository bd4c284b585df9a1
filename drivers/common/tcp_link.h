// TCP on both sides of a link: the host side connects to a serial-to-network bridge (ser2net,
// a device server, or an emulator's TCP port); the device side of an emulator listens and
// serves one client at a time.
#pragma once

#include <memory>
#include <string>

#include "drivers/common/fd_byte_stream.h"

namespace slammtt {

struct TcpEndpoint {
  std::string host;  // name or address; an IPv6 address without its brackets
  int port = 0;
};

// Parses "tcp://HOST:PORT" (IPv6 as "tcp://[::1]:PORT"). Throws std::invalid_argument with a
// one-line reason for anything else.
TcpEndpoint ParseTcpEndpoint(const std::string& endpoint);
// True when `endpoint` starts with "tcp://" (it names a TCP link, well formed or not).
bool IsTcpEndpoint(const std::string& endpoint);

// Connects to HOST:PORT within `timeout_ms` (name resolution included), trying every address
// the name resolves to. TCP_NODELAY is set: requests are a few bytes and must leave at once.
// Throws LinkError "tcp://HOST:PORT: connection refused" and the like.
std::unique_ptr<FdByteStream> ConnectTcp(const TcpEndpoint& endpoint, int timeout_ms);

// The device side of an emulator: listens on a TCP port and hands out one client at a time.
// A new client replaces the current one (the emulator drops the old stream), as a device
// server that lost its peer without noticing would: the host that reconnects must win.
class TcpDeviceServer {
 public:
  // Listens on `bind_host` ("127.0.0.1", "0.0.0.0", "::1") and `port`; 0 picks a free port
  // (see port()). SO_REUSEADDR, so an emulator restarted at once gets its port back.
  // Throws LinkError naming the address when it cannot listen.
  TcpDeviceServer(const std::string& bind_host, int port);
  ~TcpDeviceServer();
  TcpDeviceServer(const TcpDeviceServer&) = delete;
  TcpDeviceServer& operator=(const TcpDeviceServer&) = delete;

  // Waits up to `timeout_ms` for a client; nullptr when none came (or while not listening).
  std::unique_ptr<FdByteStream> Accept(int timeout_ms);
  // Closes the listening socket: new connections are refused, as when a device is unplugged
  // from its bridge. Listen() opens it again on the same port.
  void StopListening();
  void Listen();
  bool listening() const { return listen_fd_ >= 0; }

  int port() const { return port_; }
  // "tcp://HOST:PORT", what a driver is given to reach this server.
  std::string Endpoint() const;

 private:
  std::string bind_host_;
  int port_;
  int listen_fd_ = -1;
};

}  // namespace slammtt
