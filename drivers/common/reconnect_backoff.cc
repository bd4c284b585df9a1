#include "drivers/common/reconnect_backoff.h"

#include <algorithm>

namespace slammtt {

ReconnectBackoff::ReconnectBackoff(int64_t initial_ms, int64_t max_ms)
    : initial_ms_(std::max<int64_t>(1, initial_ms)),
      max_ms_(std::max(max_ms, std::max<int64_t>(1, initial_ms))),
      next_ms_(initial_ms_) {}

int64_t ReconnectBackoff::NextDelayMs() {
  const int64_t delay = next_ms_;
  next_ms_ = std::min(max_ms_, next_ms_ * 2);
  ++failures_;
  return delay;
}

void ReconnectBackoff::Reset() {
  next_ms_ = initial_ms_;
  failures_ = 0;
}

}  // namespace slammtt
