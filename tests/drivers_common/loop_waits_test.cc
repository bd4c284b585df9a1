// A session's waits as turns of the process's loop (drivers/common/loop_waits.h): while the
// link is silent the loop serves the bus and its timers; the link's bytes end the wait.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "drivers/common/driver_clock.h"
#include "drivers/common/fd_byte_stream.h"
#include "drivers/common/loop_waits.h"
#include "runtime/event_loop.h"
#include "runtime/memory_bus.h"
#include "runtime/shutdown.h"

namespace slammtt {
namespace {

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

class LoopWaitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    int fds[2];
    ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
    device_fd_ = fds[1];
    link_ = std::make_unique<LoopWaitingByteStream>(
        std::make_unique<FdByteStream>(fds[0], "test-link"), &loop_);
  }
  void TearDown() override {
    if (device_fd_ >= 0) close(device_fd_);
  }

  MemoryBus bus_;
  SteadyMonotonicClock clock_;
  EventLoop loop_{&bus_, &clock_};
  int device_fd_ = -1;
  std::unique_ptr<LoopWaitingByteStream> link_;
};

TEST_F(LoopWaitsTest, ASilentLinkWaitsItsTimeoutWhileTheLoopServesBusAndTimers) {
  int messages = 0;
  int ticks = 0;
  bus_.SubscribeBytes("X", [&](const std::string&, const void*, int) { ++messages; });
  loop_.AddTimer(10000, [&] { ++ticks; });
  bus_.Publish("X", "1", 1);
  uint8_t buffer[16];
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(link_->Read(buffer, sizeof buffer, 100), 0u);
  EXPECT_GE(MillisecondsSince(start), 99.0);
  EXPECT_EQ(messages, 1);
  EXPECT_GE(ticks, 3);  // 10 ms timer in a 100 ms wait: at least a few, on a loaded machine
  EXPECT_EQ(link_->Describe(), "test-link");
}

TEST_F(LoopWaitsTest, TheLinksBytesEndTheWait) {
  std::thread device([this] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    EXPECT_EQ(write(device_fd_, "abc", 3), 3);
  });
  uint8_t buffer[16];
  const auto start = std::chrono::steady_clock::now();
  size_t got = 0;
  while (got == 0 && MillisecondsSince(start) < 5000.0) {
    got = link_->Read(buffer, sizeof buffer, 10000);
  }
  device.join();
  ASSERT_EQ(got, 3u);
  EXPECT_EQ(std::string(reinterpret_cast<char*>(buffer), 3), "abc");
  EXPECT_LT(MillisecondsSince(start), 5000.0);  // the bytes, not the 10 s timeout, ended it
  // The hook is gone after the read: the loop no longer watches the link.
  ASSERT_EQ(write(device_fd_, "d", 1), 1);
  EXPECT_EQ(loop_.HandleTimeout(0), 0);
}

TEST_F(LoopWaitsTest, AHungUpLinkIsALinkError) {
  close(device_fd_);
  device_fd_ = -1;
  uint8_t buffer[16];
  EXPECT_THROW(link_->Read(buffer, sizeof buffer, 1000), LinkError);
}

TEST_F(LoopWaitsTest, SleepTurnsTheLoopForItsWholeDuration) {
  SystemDriverClock system_clock;
  LoopWaitingDriverClock clock(&system_clock, &loop_);
  int ticks = 0;
  loop_.AddTimer(5000, [&] { ++ticks; });
  const int64_t start_us = clock.NowMonotonicUs();
  clock.SleepUs(50000);
  EXPECT_GE(clock.NowMonotonicUs() - start_us, 50000);
  EXPECT_GE(ticks, 3);
  // After a shutdown request the loop no longer waits: the sleep is a plain one.
  RequestShutdown();
  const int64_t late_us = clock.NowMonotonicUs();
  clock.SleepUs(20000);
  EXPECT_GE(clock.NowMonotonicUs() - late_us, 20000);
  ResetShutdown();
}

}  // namespace
}  // namespace slammtt
