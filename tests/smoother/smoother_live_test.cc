// slammtt-smoother live: the estimator's SMOOTHER_INPUT of a replay played with lcm-logplayer
// into the process, recorded with lcm-logger, gives byte for byte the SMOOTHED_POSE and
// SMOOTHED_MAP that slammtt-replay computes from the same messages (the smoother has one input
// channel, so unlike the estimator no interleaving can differ). Runs in a network namespace of
// its own (NETNS), so no packet leaves it.
#include <signal.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "runtime/lcm_io.h"
#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;
using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

using testing::MessagesByChannel;
using testing::WaitFor;

int Interrupt(ChildProcess* child) {
  child->Signal(SIGINT);
  return child->Wait(20000).value_or(-1);
}

TEST(SmootherLiveTest, TheLiveProcessComputesWhatReplayComputes) {
  testing::TempDir dir;
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-world") + " --scenario s1-crossing --seed 2 --duration 15 --log " +
                      dir.File("world.lcm"),
                  &out),
            0)
      << out;
  const std::string config = std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/s1-crossing.yaml";
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --no-timing --smoother " + dir.File("world.lcm") +
                      " -o " + dir.File("replay.lcm") + " --config " + config,
                  &out),
            0)
      << out;
  const auto replay = MessagesByChannel(dir.File("replay.lcm"));
  const size_t scans = replay.at("SMOOTHER_INPUT").size();
  ASSERT_GT(scans, 100u);

  // A 4 MB receive buffer for every process on the bus, as tools_replay_live_test explains.
  const std::string bus_url = std::string(kDefaultLcmUrl) + "&recv_buf_size=4194304";
  ASSERT_EQ(setenv("LCM_DEFAULT_URL", bus_url.c_str(), 1), 0);
  ChildProcess smoother({Bin("slammtt-smoother"), "--config", config}, dir.File("smoother.txt"));
  ASSERT_TRUE(WaitFor(
      [&] {
        return ReadWholeFile(dir.File("smoother.txt")).find("smoothing") != std::string::npos;
      },
      20.0))
      << ReadWholeFile(dir.File("smoother.txt"));
  ChildProcess logger({"lcm-logger", "-f", "--flush-interval=20", dir.File("live.lcm")},
                      dir.File("logger.txt"));
  const std::unique_ptr<lcm::LCM> bus = OpenLcm(bus_url);
  const std::string probe = "ready?";
  ASSERT_TRUE(WaitFor(
      [&] {
        bus->publish("SMOOTHER_LIVE_TEST_PROBE", probe.data(),
                     static_cast<unsigned>(probe.size()));
        return MessagesByChannel(dir.File("live.lcm")).count("SMOOTHER_LIVE_TEST_PROBE") != 0;
      },
      20.0));

  ChildProcess player({"lcm-logplayer", "--speed=4", "--regexp=SMOOTHER_INPUT",
                       dir.File("replay.lcm")},
                      dir.File("player.txt"));
  ASSERT_EQ(player.Wait(120000), 0) << ReadWholeFile(dir.File("player.txt"));
  WaitFor([&] { return MessagesByChannel(dir.File("live.lcm"))["SMOOTHED_POSE"].size() >= scans; },
          30.0);
  EXPECT_EQ(Interrupt(&logger), 0);
  EXPECT_EQ(Interrupt(&smoother), 0) << ReadWholeFile(dir.File("smoother.txt"));

  auto live = MessagesByChannel(dir.File("live.lcm"));
  ASSERT_EQ(live["SMOOTHER_INPUT"], replay.at("SMOOTHER_INPUT")) << "the recording lost input";
  EXPECT_EQ(live["SMOOTHED_POSE"], replay.at("SMOOTHED_POSE"));
  EXPECT_EQ(live["SMOOTHED_MAP"], replay.at("SMOOTHED_MAP"));
  EXPECT_EQ(live["STAGE_TIMING"].size(), scans);
  EXPECT_NE(ReadWholeFile(dir.File("smoother.txt")).find("stopped: " + std::to_string(scans) +
                                                         " scans"),
            std::string::npos)
      << ReadWholeFile(dir.File("smoother.txt"));
}

}  // namespace
}  // namespace slammtt
