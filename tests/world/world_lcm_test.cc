// slammtt-world on a live bus (runs in a network namespace of its own: NETNS in CMake). A
// separate process, lcm-logger, records the bus while slammtt-world runs in real time (sped up);
// the recording must hold every message of every channel, in order, and the same messages as
// the log written as fast as possible (only utime differs: live runs start at the wall clock).
// Also: lcm-logplayer plays a fast-mode log; SIGINT and SIGTERM end a live run with status 0.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ProcessResult;
using testing::ReadWholeFile;
using testing::RunProcess;

const std::string kWorld = std::string(SLAMMTT_BIN_DIR) + "/slammtt-world";
const std::string kUrl = "udpm://239.255.76.67:7667?ttl=0";
constexpr int64_t kEpoch = 1700000000000000;

// The events of one channel group of a log, in log order.
std::vector<LogEvent> ReadEvents(const std::string& path,
                                 const std::vector<std::string>& channels) {
  std::vector<LogEvent> events;
  LogReader log(path);
  while (std::optional<LogEvent> e = log.Next()) {
    if (std::find(channels.begin(), channels.end(), e->channel) != channels.end()) {
      events.push_back(std::move(*e));
    }
  }
  return events;
}

bool LogHasChannel(const std::string& path, const std::string& channel) {
  if (!fs::exists(path) || fs::file_size(path) == 0) return false;
  try {
    return !ReadEvents(path, {channel}).empty();
  } catch (const std::exception&) {
    return false;
  }
}

// Shifts the utime of a world message by -offset and re-encodes it.
std::vector<uint8_t> Unshift(const LogEvent& e, int64_t offset, int64_t* utime, int64_t* sequence) {
  const int size = static_cast<int>(e.data.size());
  *sequence = -1;
  if (e.channel == "ODOMETRY") {
    slammtt_msgs::odometry_t m{};
    EXPECT_TRUE(Decode(e.data.data(), size, &m));
    *utime = m.utime;
    *sequence = m.sequence;
    m.utime -= offset;
    return Encode(m);
  }
  if (e.channel == "GROUND_TRUTH") {
    slammtt_msgs::ground_truth_t m{};
    EXPECT_TRUE(Decode(e.data.data(), size, &m));
    *utime = m.utime;
    m.utime -= offset;
    return Encode(m);
  }
  if (e.channel == "LASER_SCAN") {
    slammtt_msgs::laser_scan_t m{};
    EXPECT_TRUE(Decode(e.data.data(), size, &m));
    *utime = m.utime;
    *sequence = m.sequence;
    m.utime -= offset;
    return Encode(m);
  }
  slammtt_msgs::features_t m{};
  EXPECT_TRUE(Decode(e.data.data(), size, &m));
  *utime = m.utime;
  *sequence = m.sequence;
  m.utime -= offset;
  return Encode(m);
}

class WorldLcmTest : public ::testing::Test {
 protected:
  void SetUp() override { lcm_ = OpenLcm(kUrl); }
  void TearDown() override { logger_.reset(); }  // killed if still running
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // Starts lcm-logger on the bus and waits until it records (a PROBE message reaches its file).
  void StartLogger(const std::string& path) {
    logger_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"lcm-logger", "-q", "-f", "--flush-interval=20",
                                 "--lcm-url=" + kUrl, path},
        Path("logger.out"), Path("logger.err"));
    WaitForMarker(path, "PROBE_START");
  }
  // Publishes `channel` until the logger's file has it (at most 20 s).
  void WaitForMarker(const std::string& path, const std::string& channel) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    slammtt_msgs::velocity_command_t probe{};
    while (!LogHasChannel(path, channel)) {
      ASSERT_LT(std::chrono::steady_clock::now(), deadline)
          << "lcm-logger never recorded " << channel << ": " << ReadWholeFile(Path("logger.err"));
      lcm_->publish(channel, &probe);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  // Marks the end (every earlier message has reached the logger once the marker has) and stops it.
  void StopLogger(const std::string& path) {
    WaitForMarker(path, "PROBE_END");
    logger_->Signal(SIGINT);
    EXPECT_EQ(logger_->Wait(20000), 0);
    logger_.reset();
  }

  testing::TempDir temp_{"slammtt-world-lcm"};  // removed with its content after the test
  const fs::path dir_ = temp_.path();
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<ChildProcess> logger_;
};

TEST_F(WorldLcmTest, LoggerInAnotherProcessReceivesEveryMessageInOrder) {
  const std::vector<std::string> channels = {"ODOMETRY", "GROUND_TRUTH", "LASER_SCAN", "FEATURES"};
  const std::vector<std::string> common = {"--scenario", "s1-crossing", "--seed", "3", "--output",
                                           "both", "--duration", "6"};
  std::vector<std::string> fast = {kWorld};
  fast.insert(fast.end(), common.begin(), common.end());
  fast.insert(fast.end(), {"--log", Path("fast.lcm")});
  ASSERT_EQ(RunProcess(fast, dir_.string()).exit_code, 0);

  StartLogger(Path("bus.lcm"));
  std::vector<std::string> live = {kWorld};
  live.insert(live.end(), common.begin(), common.end());
  live.insert(live.end(), {"--rate-factor", "10", "--lcm-url", kUrl});
  const ProcessResult run = RunProcess(live, dir_.string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("for 6.00 s simulated"), std::string::npos) << run.err;
  StopLogger(Path("bus.lcm"));

  const std::vector<LogEvent> expected = ReadEvents(Path("fast.lcm"), channels);
  const std::vector<LogEvent> recorded = ReadEvents(Path("bus.lcm"), channels);
  // 6 s: 121 odometry readings (20 Hz), 49 scan times (8 Hz) with three messages each.
  ASSERT_EQ(expected.size(), 121u + 49u * 3u);
  ASSERT_EQ(recorded.size(), expected.size());

  std::map<std::string, int64_t> next_sequence;
  int64_t offset = 0;
  int64_t last_utime = 0;
  for (size_t i = 0; i < recorded.size(); ++i) {
    ASSERT_EQ(recorded[i].channel, expected[i].channel) << i;
    int64_t utime = 0;
    int64_t sequence = -1;
    if (i == 0) {
      int64_t ignored_utime = 0;
      Unshift(recorded[0], 0, &ignored_utime, &sequence);
      offset = ignored_utime - kEpoch;  // live: first message at the wall clock
      EXPECT_GT(offset, 0);
    }
    const std::vector<uint8_t> unshifted = Unshift(recorded[i], offset, &utime, &sequence);
    EXPECT_GE(utime, last_utime) << i;
    last_utime = utime;
    if (sequence >= 0) {
      EXPECT_EQ(sequence, next_sequence[recorded[i].channel]) << recorded[i].channel;
      next_sequence[recorded[i].channel] = sequence + 1;
    }
    EXPECT_TRUE(unshifted == expected[i].data) << "message " << i << " on " << recorded[i].channel;
  }
}

TEST_F(WorldLcmTest, LogplayerPlaysAFastModeLog) {
  const ProcessResult made = RunProcess(
      {kWorld, "--scenario", "rplidar-a2", "--duration", "3", "--log", Path("fast.lcm")},
      dir_.string());
  ASSERT_EQ(made.exit_code, 0) << made.err;
  StartLogger(Path("bus.lcm"));
  const ProcessResult played = RunProcess(
      {"lcm-logplayer", "--speed=5", "--lcm-url=" + kUrl, Path("fast.lcm")}, dir_.string());
  ASSERT_EQ(played.exit_code, 0) << played.err;
  StopLogger(Path("bus.lcm"));
  const std::vector<std::string> channels = {"ODOMETRY", "GROUND_TRUTH", "LASER_SCAN"};
  const std::vector<LogEvent> expected = ReadEvents(Path("fast.lcm"), channels);
  const std::vector<LogEvent> recorded = ReadEvents(Path("bus.lcm"), channels);
  EXPECT_EQ(expected.size(), 61u + 31u + 31u);
  ASSERT_EQ(recorded.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(recorded[i].channel, expected[i].channel);
    EXPECT_TRUE(recorded[i].data == expected[i].data) << i;  // played as written
  }
}

struct TruthLog {
  std::vector<slammtt_msgs::ground_truth_t> messages;
};

void OnTruth(const lcm::ReceiveBuffer* rbuf, const std::string&, TruthLog* log) {
  slammtt_msgs::ground_truth_t m{};
  if (Decode(rbuf->data, static_cast<int>(rbuf->data_size), &m)) log->messages.push_back(m);
}

TEST_F(WorldLcmTest, FollowCommandsDrivesTheRobotAndStopsWhenCommandsStop) {
  TruthLog truth;
  lcm_->subscribeFunction("GROUND_TRUTH", &OnTruth, &truth);
  // Real time, 4 s: commands at 20 Hz during the first wall second only (after the world is
  // up); the robot must move forward and then stop (0.5 s command timeout).
  ChildProcess world({kWorld, "--scenario", "rplidar-a2", "--duration", "4", "--follow-commands",
                      "--lcm-url", kUrl},
                     Path("world.out"), Path("world.err"));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (truth.messages.empty() && std::chrono::steady_clock::now() < deadline) {
    lcm_->handleTimeout(50);
  }
  ASSERT_FALSE(truth.messages.empty()) << ReadWholeFile(Path("world.err"));
  slammtt_msgs::velocity_command_t command{};
  command.linear_mps = 0.5;
  command.angular_radps = 0.0;
  const auto commands_end = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (std::chrono::steady_clock::now() < commands_end) {
    lcm_->publish("VELOCITY_COMMAND", &command);
    lcm_->handleTimeout(50);
  }
  std::optional<int> exit_code;
  while (!exit_code && std::chrono::steady_clock::now() < deadline) {
    lcm_->handleTimeout(50);
    exit_code = world.Wait(0);
  }
  // (Still running: killed by ChildProcess's destructor.)
  ASSERT_TRUE(exit_code.has_value()) << "slammtt-world did not end: "
                                     << ReadWholeFile(Path("world.err"));
  EXPECT_EQ(*exit_code, 0) << ReadWholeFile(Path("world.err"));
  for (int i = 0; i < 5; ++i) lcm_->handleTimeout(20);
  ASSERT_GE(truth.messages.size(), 20u);
  const slammtt_msgs::ground_truth_t& first = truth.messages.front();
  const slammtt_msgs::ground_truth_t& last = truth.messages.back();
  EXPECT_EQ(first.robot_linear_mps, 0.0);  // stands until commanded
  bool drove = false;
  for (const auto& m : truth.messages) drove = drove || m.robot_linear_mps == 0.5;
  EXPECT_TRUE(drove);
  EXPECT_EQ(last.robot_linear_mps, 0.0);  // stopped after the commands stopped
  // About 1 s of commands plus up to the 0.5 s timeout at 0.5 m/s; the scenario's own waypoint
  // motion (0.25 m/s) would not reach this.
  const double travelled =
      std::hypot(last.robot_x_m - first.robot_x_m, last.robot_y_m - first.robot_y_m);
  EXPECT_GT(travelled, 0.3);
  EXPECT_LT(travelled, 1.0);
  EXPECT_NEAR(last.robot_heading_rad, 0.0, 1e-9);
}

TEST_F(WorldLcmTest, LiveRunStopsCleanlyOnSigintAndSigterm) {
  // Real time, with and without --follow-commands (which waits in LCM's select: the signal
  // interrupts it and must read as a shutdown request, not as a failed bus).
  for (const int signal_number : {SIGINT, SIGTERM}) {
    for (const bool follow : {false, true}) {
      SCOPED_TRACE(std::string(signal_number == SIGINT ? "SIGINT" : "SIGTERM") +
                   (follow ? " --follow-commands" : ""));
      TruthLog truth;
      lcm::Subscription* subscription = lcm_->subscribeFunction("GROUND_TRUTH", &OnTruth, &truth);
      std::vector<std::string> argv = {kWorld, "--scenario", "rplidar-a2", "--duration", "3600",
                                       "--lcm-url", kUrl};
      if (follow) argv.push_back("--follow-commands");
      // ChildProcess appends: world.err must hold this run's lines only.
      fs::remove(Path("world.out"));
      fs::remove(Path("world.err"));
      ChildProcess world(argv, Path("world.out"), Path("world.err"));
      // Running its loop once it publishes.
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (truth.messages.size() < 3 && std::chrono::steady_clock::now() < deadline) {
        lcm_->handleTimeout(50);
      }
      lcm_->unsubscribe(subscription);
      ASSERT_GE(truth.messages.size(), 3u) << ReadWholeFile(Path("world.err"));
      world.Signal(signal_number);
      EXPECT_EQ(world.Wait(10000).value_or(-1), 0);
      const std::string err = ReadWholeFile(Path("world.err"));
      EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
      EXPECT_EQ(err.rfind("slammtt-world: info: rplidar-a2 seed 1: ", 0), 0u) << err;
      EXPECT_NE(err.find("(interrupted)\n"), std::string::npos) << err;
    }
  }
}

}  // namespace
}  // namespace slammtt
