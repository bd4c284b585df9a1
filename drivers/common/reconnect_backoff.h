// How long a driver waits before it tries to reopen a link that failed: doubling from an
// initial delay up to a ceiling, back to the initial delay after a link worked. No jitter: one
// driver per device, so there is no herd to spread, and the sequence stays reproducible.
#pragma once

#include <cstdint>

namespace slammtt {

class ReconnectBackoff {
 public:
  // initial_ms > 0, max_ms >= initial_ms (the caller validates its configuration).
  ReconnectBackoff(int64_t initial_ms, int64_t max_ms);
  // The delay before the next attempt: initial, 2x, 4x, ... capped at max.
  int64_t NextDelayMs();
  // After a successful session: the next failure waits the initial delay again.
  void Reset();
  // Attempts since the last Reset().
  int64_t failures() const { return failures_; }

 private:
  int64_t initial_ms_;
  int64_t max_ms_;
  int64_t next_ms_;
  int64_t failures_ = 0;
};

}  // namespace slammtt
