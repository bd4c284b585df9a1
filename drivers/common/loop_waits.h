// A device session's waits as turns of the process's EventLoop (runtime/event_loop.h), for a
// session written as blocking calls with bounded waits (RplidarSession): while it waits for its
// link or sleeps, the loop serves the bus, its timers and its other descriptors, so the process
// has one wait, the loop's, as a session with Poll() has (slammtt-p3dx).
//
// LoopWaitingByteStream wraps the link: Read(..., timeout_ms) hooks the link's PollDescriptor()
// into the loop, turns the loop until the link is readable (or hung up) or the timeout passed,
// and then reads what is there with a timeout of 0. A shutdown request ends the wait at once
// (Read returns 0, as a signal does: the session then asks whether to stop). A link without a
// descriptor (a test double) waits in its own Read after one turn of the loop that does not wait.
// Everything else passes through.
//
// LoopWaitingDriverClock wraps the driver's clock: SleepUs() turns the loop until the duration
// has passed (a plain sleep once shutdown is requested, when the loop no longer waits); the
// times pass through.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "runtime/event_loop.h"

namespace slammtt {

class LoopWaitingByteStream : public ByteStream {
 public:
  // `loop` outlives the stream.
  LoopWaitingByteStream(std::unique_ptr<ByteStream> link, EventLoop* loop);

  void Write(const uint8_t* data, size_t size, int timeout_ms = 1000) override {
    link_->Write(data, size, timeout_ms);
  }
  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override;
  void FlushInput() override { link_->FlushInput(); }
  void SetDtr(bool asserted) override { link_->SetDtr(asserted); }
  std::string Describe() const override { return link_->Describe(); }
  int PollDescriptor() const override { return link_->PollDescriptor(); }

 private:
  std::unique_ptr<ByteStream> link_;
  EventLoop* loop_;
};

class LoopWaitingDriverClock : public DriverClock {
 public:
  // `clock` and `loop` outlive this one.
  LoopWaitingDriverClock(DriverClock* clock, EventLoop* loop) : clock_(clock), loop_(loop) {}

  int64_t NowUtime() override { return clock_->NowUtime(); }
  int64_t NowMonotonicUs() override { return clock_->NowMonotonicUs(); }
  void SleepUs(int64_t duration_us) override;

 private:
  DriverClock* clock_;
  EventLoop* loop_;
};

}  // namespace slammtt
