#include "drivers/common/driver_clock.h"

#include <time.h>

namespace slammtt {
namespace {

int64_t Read(clockid_t clock) {
  struct timespec now = {};
  clock_gettime(clock, &now);
  return static_cast<int64_t>(now.tv_sec) * 1000000 + now.tv_nsec / 1000;
}

}  // namespace

int64_t SystemDriverClock::NowUtime() { return Read(CLOCK_REALTIME); }
int64_t SystemDriverClock::NowMonotonicUs() { return Read(CLOCK_MONOTONIC); }

}  // namespace slammtt
