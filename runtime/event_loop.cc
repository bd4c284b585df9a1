#include "runtime/event_loop.h"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "runtime/shutdown.h"

namespace slammtt {

namespace {

// Run() wakes at least this often (the shutdown descriptor wakes it at once anyway).
constexpr int kRunMaxWaitMs = 1000;

}  // namespace

int64_t SteadyMonotonicClock::NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

EventLoop::EventLoop(Bus* bus, MonotonicClock* clock) : bus_(bus), clock_(clock) {}

int EventLoop::AddTimer(int64_t period_us, std::function<void()> on_due) {
  if (period_us <= 0) throw std::invalid_argument("EventLoop::AddTimer: period must be > 0");
  timers_.push_back(Timer{next_id_, period_us, clock_->NowUs() + period_us, std::move(on_due)});
  return next_id_++;
}

void EventLoop::RemoveTimer(int id) {
  timers_.erase(std::remove_if(timers_.begin(), timers_.end(),
                               [id](const Timer& t) { return t.id == id; }),
                timers_.end());
}

int EventLoop::AddFdHook(int fd, std::function<void()> on_readable) {
  return AddFdHook([fd] { return fd; }, std::move(on_readable));
}

int EventLoop::AddFdHook(std::function<int()> current_fd, std::function<void()> on_readable) {
  fd_hooks_.push_back(FdHook{next_id_, std::move(current_fd), std::move(on_readable)});
  return next_id_++;
}

void EventLoop::RemoveFdHook(int id) {
  fd_hooks_.erase(std::remove_if(fd_hooks_.begin(), fd_hooks_.end(),
                                 [id](const FdHook& h) { return h.id == id; }),
                  fd_hooks_.end());
}

int64_t EventLoop::MicrosecondsUntilNextTimer() {
  if (timers_.empty()) return -1;
  int64_t due = timers_.front().due_us;
  for (const Timer& t : timers_) due = std::min(due, t.due_us);
  return std::max<int64_t>(0, due - clock_->NowUs());
}

int EventLoop::HandleTimeout(int timeout_ms) {
  if (timeout_ms < 0) throw std::invalid_argument("EventLoop::HandleTimeout: negative timeout");
  return HandleTimeoutUs(static_cast<int64_t>(timeout_ms) * 1000);
}

int EventLoop::HandleTimeoutUs(int64_t timeout_us) {
  if (timeout_us < 0) throw std::invalid_argument("EventLoop::HandleTimeoutUs: negative timeout");
  int64_t wait_us = timeout_us;
  if (const int64_t timer_us = MicrosecondsUntilNextTimer(); timer_us >= 0) {
    wait_us = std::min(wait_us, timer_us);
  }
  if (bus_->HasWaiting()) wait_us = 0;

  // [0] shutdown, [1] the bus (or -1: poll ignores a negative descriptor), [2...] the hooks.
  std::vector<pollfd> fds;
  fds.reserve(2 + fd_hooks_.size());
  fds.push_back({ShutdownFd(), POLLIN, 0});
  fds.push_back({bus_->HasSubscriptions() ? bus_->WaitDescriptor() : -1, POLLIN, 0});
  std::vector<int> hook_ids;
  for (const FdHook& hook : fd_hooks_) {
    fds.push_back({hook.current_fd(), POLLIN, 0});
    hook_ids.push_back(hook.id);
  }
  const timespec wait = {static_cast<time_t>(wait_us / 1000000),
                         static_cast<long>((wait_us % 1000000) * 1000)};
  const int ready = ppoll(fds.data(), fds.size(), &wait, nullptr);
  if (ready < 0 && errno != EINTR) {
    throw std::runtime_error(std::string("poll failed: ") + std::strerror(errno));
  }

  int handled = 0;
  if (bus_->HasWaiting() || (ready > 0 && (fds[1].revents & POLLIN) != 0)) {
    handled += bus_->Handle();
  }
  if (ready > 0) {
    for (size_t k = 2; k < fds.size(); ++k) {
      if (fds[k].fd < 0 || (fds[k].revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL)) == 0) {
        continue;
      }
      // By id: a hook may remove hooks (its own included).
      for (FdHook& hook : fd_hooks_) {
        if (hook.id != hook_ids[k - 2]) continue;
        std::function<void()> on_readable = hook.on_readable;
        on_readable();
        ++handled;
        break;
      }
    }
  }
  return handled + FireDueTimers();
}

int EventLoop::FireDueTimers() {
  if (timers_.empty()) return 0;  // a loop without timers never reads its clock
  const int64_t now_us = clock_->NowUs();
  int fired = 0;
  while (true) {
    // The earliest due timer, the first added among equals (ids grow in order of adding).
    Timer* next = nullptr;
    for (Timer& t : timers_) {
      if (t.due_us > now_us) continue;
      if (next == nullptr || t.due_us < next->due_us ||
          (t.due_us == next->due_us && t.id < next->id)) {
        next = &t;
      }
    }
    if (next == nullptr) return fired;
    const int64_t periods_late = (now_us - next->due_us) / next->period_us;
    timer_periods_skipped_ += periods_late;
    next->due_us += (periods_late + 1) * next->period_us;
    // A copy: the handler may add or remove timers, which moves the vector's elements.
    std::function<void()> on_due = next->on_due;
    on_due();
    ++fired;
  }
}

void EventLoop::Run() {
  while (!ShutdownRequested()) HandleTimeout(kRunMaxWaitMs);
}

}  // namespace slammtt
