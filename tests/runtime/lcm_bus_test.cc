// Runs in a network namespace of its own (NETNS in CMake): multicast on loopback only.
#include <gtest/gtest.h>

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
  auto lcm = OpenLcm("udpm://239.255.76.67:7667?ttl=0");
  DoublingStage stage;
  LiveStageRunner runner(lcm.get());
  runner.Add(&stage);

  std::vector<double> echoed;
  lcm->subscribeFunction(
      "ECHO",
      +[](const lcm::ReceiveBuffer* rbuf, const std::string&, std::vector<double>* out) {
        slammtt_msgs::velocity_command_t cmd;
        if (Decode(rbuf->data, static_cast<int>(rbuf->data_size), &cmd)) {
          out->push_back(cmd.linear_mps);
        }
      },
      &echoed);

  slammtt_msgs::velocity_command_t cmd{};
  cmd.linear_mps = 0.25;
  lcm->publish("VELOCITY_COMMAND", &cmd);
  const char garbage[3] = {1, 2, 3};
  lcm->publish("VELOCITY_COMMAND", garbage, 3);
  for (int i = 0; i < 50 && echoed.empty(); ++i) lcm->handleTimeout(100);
  for (int i = 0; i < 5; ++i) lcm->handleTimeout(20);
  ASSERT_EQ(echoed.size(), 1u);
  EXPECT_DOUBLE_EQ(echoed[0], 0.5);
  EXPECT_EQ(stage.bad_messages, 1);

  RequestShutdown();
  runner.Run(10);  // returns at once after the request
  ResetShutdown();
}

}  // namespace
}  // namespace slammtt
