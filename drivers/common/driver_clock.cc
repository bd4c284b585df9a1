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

void SystemDriverClock::SleepUs(int64_t duration_us) {
  if (duration_us <= 0) return;
  struct timespec wait = {};
  wait.tv_sec = static_cast<time_t>(duration_us / 1000000);
  wait.tv_nsec = static_cast<long>((duration_us % 1000000) * 1000);
  nanosleep(&wait, nullptr);  // a signal ends it early: callers re-check for shutdown
}

}  // namespace slammtt
