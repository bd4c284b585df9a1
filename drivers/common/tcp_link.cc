#include "drivers/common/tcp_link.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace slammtt {
namespace {

using SteadyClock = std::chrono::steady_clock;

std::string Describe(const TcpEndpoint& endpoint) {
  const bool ipv6 = endpoint.host.find(':') != std::string::npos;
  return "tcp://" + (ipv6 ? "[" + endpoint.host + "]" : endpoint.host) + ":" +
         std::to_string(endpoint.port);
}

// Connects one resolved address; returns the socket or -1 with `error` set.
int ConnectAddress(const addrinfo& address, SteadyClock::time_point deadline, int* error) {
  const int fd = socket(address.ai_family, address.ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC,
                        address.ai_protocol);
  if (fd < 0) {
    *error = errno;
    return -1;
  }
  if (connect(fd, address.ai_addr, address.ai_addrlen) == 0) return fd;
  if (errno != EINPROGRESS) {
    *error = errno;
    close(fd);
    return -1;
  }
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - SteadyClock::now())
                          .count();
    if (left <= 0) {
      *error = ETIMEDOUT;
      close(fd);
      return -1;
    }
    struct pollfd entry = {fd, POLLOUT, 0};
    const int ready = poll(&entry, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    int so_error = 0;
    socklen_t length = sizeof so_error;
    getsockopt(fd, SOL_SOCKET, SO_ERROR, &so_error, &length);
    if (so_error != 0) {
      *error = so_error;
      close(fd);
      return -1;
    }
    return fd;
  }
}

}  // namespace

bool IsTcpEndpoint(const std::string& endpoint) { return endpoint.rfind("tcp://", 0) == 0; }

TcpEndpoint ParseTcpEndpoint(const std::string& endpoint) {
  if (!IsTcpEndpoint(endpoint)) {
    throw std::invalid_argument("\"" + endpoint + "\" is not a tcp://HOST:PORT endpoint");
  }
  const std::string rest = endpoint.substr(6);
  TcpEndpoint parsed;
  std::string port_text;
  if (!rest.empty() && rest[0] == '[') {
    const size_t close_bracket = rest.find(']');
    if (close_bracket == std::string::npos || close_bracket + 1 >= rest.size() ||
        rest[close_bracket + 1] != ':') {
      throw std::invalid_argument("\"" + endpoint + "\": expected tcp://[IPV6]:PORT");
    }
    parsed.host = rest.substr(1, close_bracket - 1);
    port_text = rest.substr(close_bracket + 2);
  } else {
    const size_t colon = rest.rfind(':');
    if (colon == std::string::npos || rest.find(':') != colon) {
      throw std::invalid_argument("\"" + endpoint + "\": expected tcp://HOST:PORT");
    }
    parsed.host = rest.substr(0, colon);
    port_text = rest.substr(colon + 1);
  }
  if (parsed.host.empty()) throw std::invalid_argument("\"" + endpoint + "\": empty host");
  if (port_text.empty() || port_text.size() > 5 ||
      port_text.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument("\"" + endpoint + "\": port must be a number 1..65535");
  }
  parsed.port = std::stoi(port_text);
  if (parsed.port < 1 || parsed.port > 65535) {
    throw std::invalid_argument("\"" + endpoint + "\": port must be a number 1..65535");
  }
  return parsed;
}

std::unique_ptr<FdByteStream> ConnectTcp(const TcpEndpoint& endpoint, int timeout_ms) {
  const std::string name = Describe(endpoint);
  const auto deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
  addrinfo hints = {};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* addresses = nullptr;
  const std::string port_text = std::to_string(endpoint.port);
  const int resolved = getaddrinfo(endpoint.host.c_str(), port_text.c_str(), &hints, &addresses);
  if (resolved != 0) {
    throw LinkError(name + ": cannot resolve host: " + gai_strerror(resolved));
  }
  int error = ECONNREFUSED;
  int fd = -1;
  for (const addrinfo* address = addresses; address != nullptr && fd < 0;
       address = address->ai_next) {
    fd = ConnectAddress(*address, deadline, &error);
  }
  freeaddrinfo(addresses);
  if (fd < 0) {
    throw LinkError(name + ": " +
                    (error == ETIMEDOUT ? "connection timed out after " +
                                              std::to_string(timeout_ms) + " ms"
                                        : std::string(std::strerror(error))));
  }
  const int on = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  return std::make_unique<FdByteStream>(fd, name);
}

TcpDeviceServer::TcpDeviceServer(const std::string& bind_host, int port)
    : bind_host_(bind_host), port_(port) {
  Listen();
}

TcpDeviceServer::~TcpDeviceServer() { StopListening(); }

void TcpDeviceServer::Listen() {
  if (listen_fd_ >= 0) return;
  const std::string name = Describe(TcpEndpoint{bind_host_, port_});
  addrinfo hints = {};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICHOST;
  addrinfo* addresses = nullptr;
  const std::string port_text = std::to_string(port_);
  const int resolved = getaddrinfo(bind_host_.c_str(), port_text.c_str(), &hints, &addresses);
  if (resolved != 0 || addresses == nullptr) {
    throw LinkError(name + ": not a numeric address to listen on: " + gai_strerror(resolved));
  }
  const int fd = socket(addresses->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    const int error = errno;
    freeaddrinfo(addresses);
    throw LinkError(name + ": socket: " + std::strerror(error));
  }
  const int on = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (bind(fd, addresses->ai_addr, addresses->ai_addrlen) != 0 || listen(fd, 4) != 0) {
    const int error = errno;
    freeaddrinfo(addresses);
    close(fd);
    throw LinkError(name + ": cannot listen: " + std::strerror(error));
  }
  freeaddrinfo(addresses);
  sockaddr_storage bound = {};
  socklen_t length = sizeof bound;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length) == 0) {
    if (bound.ss_family == AF_INET) {
      port_ = ntohs(reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
    } else if (bound.ss_family == AF_INET6) {
      port_ = ntohs(reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port);
    }
  }
  listen_fd_ = fd;
}

void TcpDeviceServer::StopListening() {
  if (listen_fd_ >= 0) close(listen_fd_);
  listen_fd_ = -1;
}

std::unique_ptr<FdByteStream> TcpDeviceServer::Accept(int timeout_ms) {
  if (listen_fd_ < 0) return nullptr;
  struct pollfd entry = {listen_fd_, POLLIN, 0};
  const int ready = poll(&entry, 1, timeout_ms < 0 ? 0 : timeout_ms);
  if (ready <= 0) return nullptr;
  sockaddr_storage peer = {};
  socklen_t length = sizeof peer;
  const int fd = accept4(listen_fd_, reinterpret_cast<sockaddr*>(&peer), &length,
                         SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return nullptr;
  const int on = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  return std::make_unique<FdByteStream>(fd, Endpoint() + " (device side)");
}

std::string TcpDeviceServer::Endpoint() const {
  return Describe(TcpEndpoint{bind_host_, port_});
}

}  // namespace slammtt
