// The bus and the loop without a network: the in-memory and log backends, typed subscriptions,
// undecodable messages, handler exceptions, timers on a clock set by hand, a descriptor hook
// on a pipe, and the wait of HandleTimeout.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/event_loop.h"
#include "runtime/lcm_io.h"
#include "runtime/log_bus.h"
#include "runtime/log_reader.h"
#include "runtime/memory_bus.h"
#include "runtime/shutdown.h"
#include "runtime/stage.h"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {
namespace {

using slammtt_msgs::velocity_command_t;

velocity_command_t Command(int64_t utime, double linear_mps) {
  velocity_command_t command{};
  command.utime = utime;
  command.linear_mps = linear_mps;
  return command;
}

class FakeClock : public MonotonicClock {
 public:
  int64_t NowUs() override { return now_us; }
  int64_t now_us = 1000000;
};

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

TEST(MemoryBusTest, TypedSubscriptionGetsDecodedMessagesInPublishOrder) {
  MemoryBus bus;
  std::vector<double> speeds;
  std::vector<std::string> raw_channels;
  bus.Subscribe<velocity_command_t>(
      "CMD", [&](const velocity_command_t& c) { speeds.push_back(c.linear_mps); });
  bus.SubscribeBytes("OTHER", [&](const std::string& channel, const void*, int size) {
    raw_channels.push_back(channel + ":" + std::to_string(size));
  });
  bus.PublishMessage("CMD", Command(1, 0.25));
  bus.Publish("OTHER", "abc", 3);
  bus.PublishMessage("CMD", Command(2, 0.5));
  bus.PublishMessage("UNHEARD", Command(3, 9.0));
  EXPECT_TRUE(speeds.empty());  // nothing is delivered before Handle()
  EXPECT_EQ(bus.Handle(), 4);
  EXPECT_EQ(speeds, (std::vector<double>{0.25, 0.5}));
  EXPECT_EQ(raw_channels, (std::vector<std::string>{"OTHER:3"}));
  EXPECT_FALSE(bus.HasWaiting());
  EXPECT_EQ(bus.Handle(), 0);
}

TEST(MemoryBusTest, WhatAHandlerPublishesWaitsForTheNextHandle) {
  MemoryBus bus;
  int echoes = 0;
  bus.Subscribe<velocity_command_t>("CMD", [&](const velocity_command_t& c) {
    bus.PublishMessage("ECHO", c);
  });
  bus.Subscribe<velocity_command_t>("ECHO", [&](const velocity_command_t&) { ++echoes; });
  bus.PublishMessage("CMD", Command(1, 0.1));
  EXPECT_EQ(bus.Handle(), 1);
  EXPECT_EQ(echoes, 0);
  EXPECT_TRUE(bus.HasWaiting());
  EXPECT_EQ(bus.Handle(), 1);
  EXPECT_EQ(echoes, 1);
}

TEST(MemoryBusTest, UndecodableMessageIsCountedAndSkipped) {
  MemoryBus bus;
  std::vector<int64_t> utimes;
  bus.Subscribe<velocity_command_t>(
      "CMD", [&](const velocity_command_t& c) { utimes.push_back(c.utime); });
  bus.PublishMessage("CMD", Command(1, 0.1));
  const char garbage[3] = {1, 2, 3};
  bus.Publish("CMD", garbage, 3);
  slammtt_msgs::odometry_t odometry{};  // another type: its fingerprint does not match
  bus.PublishMessage("CMD", odometry);
  bus.Publish("CMD", nullptr, 0);
  bus.PublishMessage("CMD", Command(2, 0.2));
  EXPECT_EQ(bus.Handle(), 5);
  EXPECT_EQ(utimes, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(bus.undecodable_messages(), 3);
  EXPECT_EQ(bus.handler_exceptions(), 0);
}

TEST(MemoryBusTest, HandlerExceptionIsRethrownAfterTheMessageAndLaterMessagesWait) {
  MemoryBus bus;
  std::vector<int64_t> first;
  std::vector<int64_t> second;
  bus.Subscribe<velocity_command_t>("CMD", [&](const velocity_command_t& c) {
    first.push_back(c.utime);
    if (c.utime == 2) throw std::runtime_error("link lost");
  });
  bus.Subscribe<velocity_command_t>(
      "CMD", [&](const velocity_command_t& c) { second.push_back(c.utime); });
  for (int64_t t = 1; t <= 3; ++t) bus.PublishMessage("CMD", Command(t, 0.1));
  try {
    bus.Handle();
    FAIL() << "the handler's exception was not rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "link lost");
  }
  // The failing message still reached the other subscription; the third one waits.
  EXPECT_EQ(first, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(second, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(bus.handler_exceptions(), 1);
  EXPECT_TRUE(bus.HasWaiting());
  EXPECT_EQ(bus.Handle(), 1);
  EXPECT_EQ(second, (std::vector<int64_t>{1, 2, 3}));
}

TEST(MemoryBusTest, UnsubscribedHandlerIsNotCalledAgainEvenFromInsideAHandler) {
  MemoryBus bus;
  int calls_a = 0;
  int calls_b = 0;
  int id_b = 0;
  bus.SubscribeBytes("X", [&](const std::string&, const void*, int) {
    ++calls_a;
    bus.Unsubscribe(id_b);
  });
  id_b = bus.SubscribeBytes("X", [&](const std::string&, const void*, int) { ++calls_b; });
  bus.Publish("X", "1", 1);
  bus.Publish("X", "2", 1);
  EXPECT_EQ(bus.Handle(), 2);
  EXPECT_EQ(calls_a, 2);
  EXPECT_EQ(calls_b, 0);
}

TEST(EventLoopTest, TimersFireInOrderOfDueTimeOnTheGivenClock) {
  MemoryBus bus;
  FakeClock clock;
  EventLoop loop(&bus, &clock);
  std::vector<std::string> fired;
  loop.AddTimer(10000, [&] { fired.push_back("a@" + std::to_string(clock.now_us)); });
  loop.AddTimer(25000, [&] { fired.push_back("b@" + std::to_string(clock.now_us)); });
  EXPECT_EQ(loop.MicrosecondsUntilNextTimer(), 10000);
  EXPECT_EQ(loop.HandleTimeout(0), 0);  // nothing due yet
  for (int step = 0; step < 10; ++step) {
    clock.now_us += 5000;
    loop.HandleTimeout(0);
  }
  // Due at +10, 20, 30, 40, 50 ms (a) and +25, 50 ms (b): at +50 ms both, a first (added first).
  EXPECT_EQ(fired, (std::vector<std::string>{"a@1010000", "a@1020000", "b@1025000", "a@1030000",
                                             "a@1040000", "a@1050000", "b@1050000"}));
  EXPECT_EQ(loop.timer_periods_skipped(), 0);
}

TEST(EventLoopTest, LateTimerFiresOnceAndKeepsItsPhase) {
  MemoryBus bus;
  FakeClock clock;
  EventLoop loop(&bus, &clock);
  std::vector<int64_t> fired_at;
  const int id = loop.AddTimer(10000, [&] { fired_at.push_back(clock.now_us); });
  clock.now_us += 35000;  // due at +10, +20, +30: late by more than two periods
  EXPECT_EQ(loop.HandleTimeout(0), 1);
  EXPECT_EQ(loop.timer_periods_skipped(), 2);
  EXPECT_EQ(loop.MicrosecondsUntilNextTimer(), 5000);  // next due at +40, not +45
  clock.now_us += 5000;
  EXPECT_EQ(loop.HandleTimeout(0), 1);
  loop.RemoveTimer(id);
  clock.now_us += 100000;
  EXPECT_EQ(loop.HandleTimeout(0), 0);
  EXPECT_EQ(fired_at, (std::vector<int64_t>{1035000, 1040000}));
  EXPECT_THROW(loop.AddTimer(0, [] {}), std::invalid_argument);
}

TEST(EventLoopTest, DeliversBusMessagesAndTimersInOneTurn) {
  MemoryBus bus;
  FakeClock clock;
  EventLoop loop(&bus, &clock);
  std::vector<std::string> events;
  bus.Subscribe<velocity_command_t>("CMD", [&](const velocity_command_t& c) {
    events.push_back("cmd " + std::to_string(c.utime));
  });
  loop.AddTimer(1000, [&] { events.push_back("tick"); });
  bus.PublishMessage("CMD", Command(7, 0.0));
  clock.now_us += 1000;
  // A waiting message means no wait at all, even with a long timeout.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(loop.HandleTimeout(10000), 2);
  EXPECT_LT(MillisecondsSince(start), 5000.0);
  EXPECT_EQ(events, (std::vector<std::string>{"cmd 7", "tick"}));
}

TEST(EventLoopTest, FdHookRunsWhenThePipeIsReadable) {
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  MemoryBus bus;
  SteadyMonotonicClock clock;
  EventLoop loop(&bus, &clock);
  std::string received;
  const int hook = loop.AddFdHook(fds[0], [&] {
    char buffer[16];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n > 0) received.append(buffer, static_cast<size_t>(n));
  });
  EXPECT_EQ(loop.HandleTimeout(0), 0);  // nothing written yet
  ASSERT_EQ(write(fds[1], "ok", 2), 2);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(loop.HandleTimeout(10000), 1);
  EXPECT_LT(MillisecondsSince(start), 5000.0);  // the pipe ended the wait, not the timeout
  EXPECT_EQ(received, "ok");

  // A descriptor asked for before every wait: -1 (a closed link) is not waited on.
  loop.RemoveFdHook(hook);
  int current = -1;
  int calls = 0;
  loop.AddFdHook([&current] { return current; }, [&] {
    char buffer[16];
    if (read(fds[0], buffer, sizeof buffer) > 0) ++calls;
  });
  ASSERT_EQ(write(fds[1], "x", 1), 1);
  EXPECT_EQ(loop.HandleTimeout(0), 0);
  current = fds[0];
  EXPECT_EQ(loop.HandleTimeout(0), 1);
  EXPECT_EQ(calls, 1);
  close(fds[0]);
  close(fds[1]);
}

TEST(EventLoopTest, HandleTimeoutWaitsItsTimeoutWhenNothingIsReady) {
  MemoryBus bus;
  SteadyMonotonicClock clock;
  EventLoop loop(&bus, &clock);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(loop.HandleTimeout(30), 0);
  EXPECT_GE(MillisecondsSince(start), 29.0);
  EXPECT_THROW(loop.HandleTimeout(-1), std::invalid_argument);
  // The bus's own handle-with-timeout likewise.
  const auto bus_start = std::chrono::steady_clock::now();
  EXPECT_EQ(bus.HandleTimeout(30), 0);
  EXPECT_GE(MillisecondsSince(bus_start), 29.0);
}

TEST(EventLoopTest, RunReturnsOnShutdownRequest) {
  MemoryBus bus;
  SteadyMonotonicClock clock;
  EventLoop loop(&bus, &clock);
  int ticks = 0;
  loop.AddTimer(1000, [&] {
    if (++ticks == 3) RequestShutdown();
  });
  loop.Run();
  EXPECT_EQ(ticks, 3);
  ResetShutdown();
}

// Echoes "IN" to "OUT"; a payload "boom" is a bug that throws.
class EchoStage : public Stage {
 public:
  std::string Name() const override { return "echo"; }
  std::vector<std::string> InputChannels() const override { return {"IN"}; }
  std::vector<std::string> OutputChannels() const override { return {"OUT"}; }
  void Handle(const std::string&, const void* data, int size, MessageSink& out) override {
    if (std::string(static_cast<const char*>(data), static_cast<size_t>(size)) == "boom") {
      throw std::runtime_error("bug");
    }
    out.Publish("OUT", data, size);
  }
};

TEST(LiveStageRunnerTest, StageOutputsGoOnTheBusAndAStageExceptionIsCounted) {
  MemoryBus bus;
  FakeClock clock;
  EventLoop loop(&bus, &clock);
  EchoStage stage;
  LiveStageRunner runner(&bus);
  runner.Add(&stage);
  std::vector<std::string> out;
  bus.SubscribeBytes("OUT", [&](const std::string&, const void* data, int size) {
    out.emplace_back(static_cast<const char*>(data), static_cast<size_t>(size));
  });
  bus.Publish("IN", "a", 1);
  bus.Publish("IN", "boom", 4);
  bus.Publish("IN", "b", 1);
  EXPECT_EQ(loop.HandleTimeout(0), 3);  // no exception leaves the loop
  EXPECT_EQ(loop.HandleTimeout(0), 2);  // the echoes
  EXPECT_EQ(out, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(runner.handler_errors(), 1);
  EXPECT_EQ(bus.handler_exceptions(), 0);
}

TEST(LogBusTest, ReplaysALogThroughSubscriptionsAndWritesStampedOutputs) {
  const std::string in_path = testing::TempDir() + "/bus_in_" + std::to_string(getpid()) + ".lcm";
  const std::string out_path =
      testing::TempDir() + "/bus_out_" + std::to_string(getpid()) + ".lcm";
  {
    LogWriter writer(in_path);
    writer.WriteMessage(100, "CMD", Command(1, 0.5));
    writer.Write(150, "NOISE", "zz", 2);
    writer.WriteMessage(200, "CMD", Command(2, 1.5));
    writer.Commit();
  }
  LogBus bus(in_path, out_path);
  FakeClock log_clock;  // timers on log time
  EventLoop loop(&bus, &log_clock);
  bus.Subscribe<velocity_command_t>("CMD", [&](const velocity_command_t& c) {
    log_clock.now_us = bus.log_time_us();
    velocity_command_t doubled = c;
    doubled.linear_mps *= 2.0;
    bus.PublishMessage("DOUBLED", doubled);
  });
  int delivered = 0;
  while (!bus.InputDone()) delivered += loop.HandleTimeout(0);
  EXPECT_EQ(delivered, 3);  // one event per turn, the unsubscribed NOISE too
  EXPECT_EQ(bus.log_time_us(), 200);
  EXPECT_EQ(bus.input_result().events_read, 3);
  EXPECT_TRUE(bus.input_result().problem.empty());
  bus.Commit();

  LogReader reader(out_path);
  std::vector<std::string> out;
  while (const auto e = reader.Next()) {
    velocity_command_t c;
    ASSERT_TRUE(Decode(e->data.data(), static_cast<int>(e->data.size()), &c));
    out.push_back(e->channel + " " + std::to_string(e->timestamp_us) + " " +
                  std::to_string(c.linear_mps));
  }
  EXPECT_EQ(out, (std::vector<std::string>{"DOUBLED 100 1.000000", "DOUBLED 200 3.000000"}));
  LogBus no_output(in_path, "");
  EXPECT_THROW(no_output.Publish("X", "1", 1), std::logic_error);
  std::remove(in_path.c_str());
  std::remove(out_path.c_str());
}

}  // namespace
}  // namespace slammtt
