#include "drivers/common/loop_waits.h"

#include <utility>

#include "runtime/shutdown.h"

namespace slammtt {

LoopWaitingByteStream::LoopWaitingByteStream(std::unique_ptr<ByteStream> link, EventLoop* loop)
    : link_(std::move(link)), loop_(loop) {}

size_t LoopWaitingByteStream::Read(uint8_t* buffer, size_t capacity, int timeout_ms) {
  const int fd = link_->PollDescriptor();
  if (fd < 0) {
    loop_->HandleTimeout(0);
    return link_->Read(buffer, capacity, timeout_ms);
  }
  bool ready = false;
  const int hook = loop_->AddFdHook(fd, [&ready] { ready = true; });
  try {
    MonotonicClock& clock = loop_->clock();
    const int64_t end_us = clock.NowUs() + int64_t{timeout_ms} * 1000;
    while (!ready && !ShutdownRequested()) {
      const int64_t left_us = end_us - clock.NowUs();
      if (left_us <= 0) break;
      loop_->HandleTimeoutUs(left_us);
    }
  } catch (...) {
    loop_->RemoveFdHook(hook);
    throw;
  }
  loop_->RemoveFdHook(hook);
  return link_->Read(buffer, capacity, 0);
}

void LoopWaitingDriverClock::SleepUs(int64_t duration_us) {
  const int64_t end_us = clock_->NowMonotonicUs() + duration_us;
  for (int64_t left_us = duration_us; left_us > 0; left_us = end_us - clock_->NowMonotonicUs()) {
    if (ShutdownRequested()) {
      clock_->SleepUs(left_us);
      return;
    }
    loop_->HandleTimeoutUs(left_us);
  }
}

}  // namespace slammtt
