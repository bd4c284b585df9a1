// The one loop of a process: it waits on the bus (bus.h), the file descriptors the process
// hooks (a serial port, a TCP link), its timers and the shutdown request together, then handles
// what is ready: the waiting messages, the readable descriptors, the due timers. Every slammtt
// process runs this loop; a stage never sees it (stage.h).
//
// Time: timers run on a MonotonicClock the caller gives. A live process gives the steady clock
// (SteadyMonotonicClock); a test gives a clock it sets by hand, so that which timer fires when
// is exact and nothing reads the wall clock; a replay can give log time (LogBus::log_time_us).
//
//   LcmBus bus(settings.lcm_url);
//   SteadyMonotonicClock clock;
//   EventLoop loop(&bus, &clock);
//   bus.Subscribe<velocity_command_t>("VELOCITY_COMMAND", [&](const velocity_command_t& c) {...});
//   loop.AddTimer(100000, [&] { bus.PublishMessage("STATUS", Status()); });  // 10 Hz
//   loop.AddFdHook(port_fd, [&] { ReadPort(); });
//   loop.Run();  // until SIGINT/SIGTERM
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "runtime/bus.h"

namespace slammtt {

// Microseconds that only go forward, from any origin.
class MonotonicClock {
 public:
  virtual ~MonotonicClock() = default;
  virtual int64_t NowUs() = 0;
};

// std::chrono::steady_clock: the live processes' clock for timers and pacing.
class SteadyMonotonicClock : public MonotonicClock {
 public:
  int64_t NowUs() override;
};

class EventLoop {
 public:
  // `bus` and `clock` outlive the loop.
  EventLoop(Bus* bus, MonotonicClock* clock);

  Bus& bus() { return *bus_; }
  MonotonicClock& clock() { return *clock_; }

  // Calls `on_due` every `period_us` (> 0, else std::invalid_argument), first at now + period.
  // Due times are now + k * period, so a slow handler does not make the timer drift; a timer
  // late by more than a period fires once and goes on at its next due time in the future (the
  // periods it missed are counted in timer_periods_skipped()). Timers due together fire in
  // order of due time, then in the order they were added. Returns an id for RemoveTimer().
  int AddTimer(int64_t period_us, std::function<void()> on_due);
  void RemoveTimer(int id);

  // Calls `on_readable` when `fd` is readable, or has hung up or failed (the handler's read
  // then says so). The second form asks `current_fd` for the descriptor before every wait, for
  // a link that reopens under another descriptor; -1 means none now. Returns an id for
  // RemoveFdHook().
  int AddFdHook(int fd, std::function<void()> on_readable);
  int AddFdHook(std::function<int()> current_fd, std::function<void()> on_readable);
  void RemoveFdHook(int id);

  // Waits at most `timeout_ms` (>= 0), less when a timer is due earlier, not at all when the
  // bus has messages waiting; a message, a readable hook, the shutdown request or a signal ends
  // the wait. Then delivers the bus's waiting messages, calls the hooks of the readable
  // descriptors, and fires the due timers. Returns how many of these it handled (0: the wait
  // timed out). A handler's exception propagates (the bus's after its delivery, bus.h).
  int HandleTimeout(int timeout_ms);
  // The same with a wait in microseconds.
  int HandleTimeoutUs(int64_t timeout_us);
  // HandleTimeout() until ShutdownRequested().
  void Run();

  // Microseconds until the next timer is due (0 when one is overdue), or -1 without timers.
  int64_t MicrosecondsUntilNextTimer();
  int64_t timer_periods_skipped() const { return timer_periods_skipped_; }

 private:
  struct Timer {
    int id;
    int64_t period_us;
    int64_t due_us;
    std::function<void()> on_due;
  };
  struct FdHook {
    int id;
    std::function<int()> current_fd;
    std::function<void()> on_readable;
  };
  int FireDueTimers();

  Bus* bus_;
  MonotonicClock* clock_;
  std::vector<Timer> timers_;
  std::vector<FdHook> fd_hooks_;
  int next_id_ = 1;
  int64_t timer_periods_skipped_ = 0;
};

}  // namespace slammtt
