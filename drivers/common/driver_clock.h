// The time a driver reads, behind an interface so tests can drive it. A driver is the one
// place in the stack that reads the clock for message time: it stamps what it measured with
// the host's time of arrival, and every stage downstream works from those stamps only.
#pragma once

#include <cstdint>

namespace slammtt {

class DriverClock {
 public:
  virtual ~DriverClock() = default;
  // Microseconds since the Unix epoch (CLOCK_REALTIME): the utime of messages, on the same
  // scale as lcm-logger's event timestamps.
  virtual int64_t NowUtime() = 0;
  // Microseconds of a monotonic clock (CLOCK_MONOTONIC) for timeouts, rates and backoff:
  // never jumps when the wall clock is set.
  virtual int64_t NowMonotonicUs() = 0;
  // Waits `duration_us` of the monotonic clock (a test clock just advances).
  virtual void SleepUs(int64_t duration_us) = 0;
};

// The host's clocks.
class SystemDriverClock : public DriverClock {
 public:
  int64_t NowUtime() override;
  int64_t NowMonotonicUs() override;
  void SleepUs(int64_t duration_us) override;
};

}  // namespace slammtt
