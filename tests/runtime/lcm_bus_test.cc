// Runs in a network namespace of its own (NETNS in CMake): multicast on loopback only.
#include <gtest/gtest.h>

#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/lcm_io.h"
#include "runtime/shutdown.h"
#include "runtime/stage.h"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {
namespace {

// Echoes VELOCITY_COMMAND to ECHO with the linear speed doubled.
class DoublingStage : public Stage {
 public:
  std::string Name() const override { return "doubler"; }
  std::vector<std::string> InputChannels() const override { return {"VELOCITY_COMMAND"}; }
  std::vector<std::string> OutputChannels() const override { return {"ECHO"}; }
  void Handle(const std::string&, const void* data, int size, MessageSink& out) override {
    slammtt_msgs::velocity_command_t cmd;
    if (!Decode(data, size, &cmd)) {
      ++bad_messages;
      return;
    }
    cmd.linear_mps *= 2.0;
    out.PublishMessage("ECHO", cmd);
    StageTimer timer(Name(), cmd.utime);
    timer.Lap("double");
    timer.Count("messages", 1);
    out.PublishMessage("STAGE_TIMING", timer.Finish());
  }
  int bad_messages = 0;
};

TEST(LcmBusTest, LiveStageRunnerHandlesAndPublishes) {
  LcmBus bus("udpm://239.255.76.67:7667?ttl=0");
  SteadyMonotonicClock clock;
  EventLoop loop(&bus, &clock);
  DoublingStage stage;
  LiveStageRunner runner(&bus);
  runner.Add(&stage);

  std::vector<double> echoed;
  bus.Subscribe<slammtt_msgs::velocity_command_t>(
      "ECHO", [&echoed](const slammtt_msgs::velocity_command_t& cmd) {
        echoed.push_back(cmd.linear_mps);
      });

  slammtt_msgs::velocity_command_t cmd{};
  cmd.linear_mps = 0.25;
  bus.PublishMessage("VELOCITY_COMMAND", cmd);
  const char garbage[3] = {1, 2, 3};
  bus.Publish("VELOCITY_COMMAND", garbage, 3);
  for (int i = 0; i < 50 && echoed.empty(); ++i) loop.HandleTimeout(100);
  for (int i = 0; i < 5; ++i) loop.HandleTimeout(20);
  ASSERT_EQ(echoed.size(), 1u);
  EXPECT_DOUBLE_EQ(echoed[0], 0.5);
  EXPECT_EQ(stage.bad_messages, 1);
  EXPECT_EQ(runner.handler_errors(), 0);

  RequestShutdown();
  loop.Run();  // returns at once after the request
  ResetShutdown();
}

// A typed subscription on LCM: an undecodable message is counted, a handler's exception comes
// out of HandleTimeout (not through LCM's C dispatch) and the bus goes on.
TEST(LcmBusTest, TypedSubscriptionCountsUndecodableAndRethrowsHandlerErrors) {
  LcmBus bus("udpm://239.255.76.67:7667?ttl=0");
  std::vector<int64_t> utimes;
  bus.Subscribe<slammtt_msgs::velocity_command_t>(
      "CMD.X", [&utimes](const slammtt_msgs::velocity_command_t& cmd) {
        utimes.push_back(cmd.utime);
        if (cmd.utime == 2) throw std::runtime_error("refused");
      });
  slammtt_msgs::velocity_command_t cmd{};
  bus.Publish("CMD.X", "bad", 3);
  bus.Publish("CMDxX", "not this channel: '.' is no pattern", 35);
  cmd.utime = 2;
  bus.PublishMessage("CMD.X", cmd);
  bool thrown = false;
  for (int i = 0; i < 50 && !thrown; ++i) {
    try {
      bus.HandleTimeout(100);
    } catch (const std::runtime_error& e) {
      thrown = std::string(e.what()) == "refused";
    }
  }
  EXPECT_TRUE(thrown);
  cmd.utime = 3;
  bus.PublishMessage("CMD.X", cmd);
  for (int i = 0; i < 50 && utimes.size() < 2; ++i) bus.HandleTimeout(100);
  EXPECT_EQ(utimes, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(bus.undecodable_messages(), 1);
  EXPECT_EQ(bus.handler_exceptions(), 1);
}

}  // namespace
}  // namespace slammtt
