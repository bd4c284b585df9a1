#include "drivers/common/byte_stream.h"

#include <stdexcept>

#include "drivers/common/serial_port_stream.h"
#include "drivers/common/tcp_link.h"

namespace slammtt {
namespace {

const char kSerialPrefix[] = "serial:";

std::string SerialPath(const std::string& endpoint) {
  return endpoint.rfind(kSerialPrefix, 0) == 0 ? endpoint.substr(sizeof kSerialPrefix - 1)
                                               : endpoint;
}

}  // namespace

void CheckEndpoint(const std::string& endpoint, int baud) {
  if (endpoint.empty()) throw std::invalid_argument("empty endpoint: give a serial port path or tcp://HOST:PORT");
  if (IsTcpEndpoint(endpoint)) {
    ParseTcpEndpoint(endpoint);
    return;
  }
  const std::string path = SerialPath(endpoint);
  if (path.empty() || path[0] != '/') {
    throw std::invalid_argument("\"" + endpoint +
                                "\": a serial port is an absolute path (/dev/ttyUSB0); a "
                                "network bridge is tcp://HOST:PORT");
  }
  if (baud <= 0) {
    throw std::invalid_argument("\"" + endpoint + "\": baud rate must be positive, got " +
                                std::to_string(baud));
  }
}

std::unique_ptr<ByteStream> OpenByteStream(const std::string& endpoint, int baud,
                                           int connect_timeout_ms) {
  try {
    CheckEndpoint(endpoint, baud);
  } catch (const std::invalid_argument& e) {
    throw LinkError(e.what());
  }
  if (IsTcpEndpoint(endpoint)) {
    return ConnectTcp(ParseTcpEndpoint(endpoint), connect_timeout_ms);
  }
  return SerialPortStream::Open(SerialPath(endpoint), baud);
}

}  // namespace slammtt
