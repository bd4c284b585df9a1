// Helpers shared by the tests of drivers/common: reading a known number of bytes with a bound,
// and asking poll() whether a descriptor is ready.
#pragma once

#include <poll.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "drivers/common/byte_stream.h"

namespace slammtt {

// Reads until `count` bytes came or 200 reads of at most 50 ms each returned (a bound against
// a hang, never a measure of speed); returns what came.
inline std::vector<uint8_t> ReadExactly(ByteStream& stream, size_t count) {
  std::vector<uint8_t> out;
  uint8_t buffer[512];
  for (int i = 0; i < 200 && out.size() < count; ++i) {
    const size_t got = stream.Read(buffer, std::min(sizeof buffer, count - out.size()), 50);
    out.insert(out.end(), buffer, buffer + got);
  }
  return out;
}

// True when poll() reports `fd` readable, hung up or failed within `timeout_ms`.
inline bool PollsReady(int fd, int timeout_ms) {
  struct pollfd entry = {fd, POLLIN, 0};
  return poll(&entry, 1, timeout_ms) == 1 && entry.revents != 0;
}

}  // namespace slammtt
