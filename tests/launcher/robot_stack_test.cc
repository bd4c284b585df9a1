// The robot's stack exactly as config/robot.yaml starts it, with the two device emulators
// standing in for the base and the laser on TCP ports (the only change to the file: the two
// device paths), as docs/robot.md shows. Runs in a network namespace of its own.
#include <gtest/gtest.h>
#include <dirent.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<std::string> FilesIn(const std::string& directory) {
  std::vector<std::string> names;
  if (DIR* dir = opendir(directory.c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name != "." && name != "..") names.push_back(name);
    }
    closedir(dir);
  }
  return names;
}

// config/robot.yaml with the two device paths replaced, both emulators on TCP ports, and
// slammtt-launch running in a temporary directory (its logs/ land there).
class RobotStack {
 public:
  RobotStack()
      : directory_(testing::MakeTempDirectory("robot-stack-test")), bin_(SLAMMTT_BIN_DIR) {
    std::string config = ReadWholeFile(std::string(SLAMMTT_SOURCE_DIR) + "/config/robot.yaml");
    EXPECT_FALSE(config.empty());
    config = Replace(config, "port: /dev/p3dx ", "port: tcp://127.0.0.1:5101 ");
    config = Replace(config, "port: /dev/rplidar", "port: tcp://127.0.0.1:5102");
    const std::string config_path = directory_ + "/robot-emulated.yaml";
    std::ofstream(config_path) << config;
    base_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin_ + "/slammtt-p3dx-emulator", "--tcp", "5101"},
        directory_ + "/base.log");
    laser_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin_ + "/slammtt-rplidar-emulator", "--tcp", "5102"},
        directory_ + "/laser.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    launcher_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin_ + "/slammtt-launch", "--config", config_path},
        directory_ + "/launch.out", directory_ + "/launch.err", directory_);
  }
  // The emulators end on SIGINT with status 0 (a launcher still running is killed first).
  ~RobotStack() {
    launcher_.reset();
    base_->Signal(SIGINT);
    laser_->Signal(SIGINT);
    EXPECT_EQ(base_->Wait(5000), 0);
    EXPECT_EQ(laser_->Wait(5000), 0);
    if (!::testing::Test::HasFailure()) testing::RemoveDirectoryTree(directory_);
  }

  // Ctrl-C: SIGINT to the launcher; its exit status, nullopt if it did not end in 30 s.
  std::optional<int> Interrupt() {
    launcher_->Signal(SIGINT);
    return launcher_->Wait(30000);
  }
  std::string Output() const {
    return ReadWholeFile(directory_ + "/launch.out") + ReadWholeFile(directory_ + "/launch.err");
  }
  // The one log the logger wrote ("" when there is not exactly one).
  std::string LogPath() const {
    const std::vector<std::string> logs = FilesIn(directory_ + "/logs");
    if (logs.size() != 1 || logs[0].rfind("slammtt-", 0) != 0) return "";
    return directory_ + "/logs/" + logs[0];
  }

 private:
  std::string directory_;
  std::string bin_;
  std::unique_ptr<ChildProcess> base_;
  std::unique_ptr<ChildProcess> laser_;
  std::unique_ptr<ChildProcess> launcher_;
};

void ExpectEveryProcessStoppedCleanly(const std::string& output) {
  for (const char* name : {"logger", "p3dx", "rplidar", "segmenter", "estimator"}) {
    EXPECT_NE(output.find(std::string(name) + " stopped (exited with status 0)"), std::string::npos)
        << name << "\n" << output;
  }
  EXPECT_NE(output.find("p3dx      | slammtt-p3dx: info: robot stopped and session closed"),
            std::string::npos) << output;
}

// The pid slammtt-launch reported for the `occurrence`-th start of `name` (0 when none).
pid_t StartedPid(const std::string& output, const std::string& name, int occurrence) {
  const std::string marker = "started " + name + " (pid ";
  size_t at = 0;
  for (int i = 0; i <= occurrence; ++i) {
    at = output.find(marker, i == 0 ? 0 : at + 1);
    if (at == std::string::npos) return 0;
  }
  return static_cast<pid_t>(std::atol(output.c_str() + at + marker.size()));
}

TEST(RobotStackTest, RobotYamlRunsTheWholeStackAgainstTheEmulators) {
  RobotStack stack;
  std::this_thread::sleep_for(std::chrono::seconds(5));
  const auto status = stack.Interrupt();
  const std::string output = stack.Output();
  ASSERT_TRUE(status.has_value()) << output;
  EXPECT_EQ(*status, 0) << output;
  ExpectEveryProcessStoppedCleanly(output);
  EXPECT_EQ(output.find("restarting"), std::string::npos) << output;

  const std::string log = stack.LogPath();
  ASSERT_FALSE(log.empty()) << output;
  LogReader reader(log);
  std::map<std::string, int> counts;
  slammtt_msgs::base_status_t last_status{};
  slammtt_msgs::odometry_t odometry{};
  while (auto event = reader.Next()) {
    ++counts[event->channel];
    if (event->channel == "BASE_STATUS") {
      ASSERT_TRUE(Decode(event->data.data(), static_cast<int>(event->data.size()), &last_status));
    }
    if (event->channel == "ODOMETRY") {
      ASSERT_TRUE(Decode(event->data.data(), static_cast<int>(event->data.size()), &odometry));
    }
  }
  // About 4 s of data: SIPs at 10 Hz, scans at 10 Hz, and what the stages make of them.
  EXPECT_GE(counts["ODOMETRY"], 25) << output;
  EXPECT_GE(counts["LASER_SCAN"], 20) << output;
  EXPECT_GE(counts["FEATURES"], 20) << output;
  EXPECT_GE(counts["POSE"], 20) << output;
  EXPECT_GE(counts["LIDAR_STATUS"], 2) << output;
  EXPECT_GE(counts["BASE_STATUS"], 3) << output;
  // The logger stops last: it recorded the driver's final status.
  EXPECT_EQ(last_status.state, "stopped");
  EXPECT_EQ(last_status.robot_subclass, "p3dx");
  EXPECT_EQ(odometry.x_m, 0.0);  // nobody commanded a motion
}

// A driver killed outright (no chance to stop its device) is started again after the backoff;
// the new process stops the scan the dead one left running and scans again, and the log goes on.
TEST(RobotStackTest, AKilledDriverIsRestartedAndScansAgain) {
  RobotStack stack;
  std::this_thread::sleep_for(std::chrono::seconds(3));
  const pid_t first = StartedPid(stack.Output(), "rplidar", 0);
  ASSERT_GT(first, 0) << stack.Output();
  ASSERT_EQ(kill(first, SIGKILL), 0);
  std::this_thread::sleep_for(std::chrono::seconds(4));  // 1 s backoff, then a new session
  const auto status = stack.Interrupt();
  const std::string output = stack.Output();
  ASSERT_TRUE(status.has_value()) << output;
  EXPECT_EQ(*status, 0) << output;
  EXPECT_NE(output.find("rplidar was killed by signal 9"), std::string::npos) << output;
  EXPECT_NE(output.find("restarting in 1 s (restart 1 of at most 5 in a row)"), std::string::npos)
      << output;
  const pid_t second = StartedPid(output, "rplidar", 1);
  EXPECT_GT(second, 0) << output;
  EXPECT_NE(second, first);
  EXPECT_EQ(StartedPid(output, "rplidar", 2), 0) << output;  // once, not a restart loop
  ExpectEveryProcessStoppedCleanly(output);

  // Each process numbers its scans from 0: the log holds both runs, the second one scanning.
  const std::string log = stack.LogPath();
  ASSERT_FALSE(log.empty()) << output;
  LogReader reader(log);
  int runs = 0;
  int scans_of_second_run = 0;
  while (auto event = reader.Next()) {
    if (event->channel != "LASER_SCAN") continue;
    slammtt_msgs::laser_scan_t scan;
    ASSERT_TRUE(Decode(event->data.data(), static_cast<int>(event->data.size()), &scan));
    if (scan.sequence == 0) ++runs;
    if (runs == 2) ++scans_of_second_run;
  }
  EXPECT_EQ(runs, 2) << output;
  EXPECT_GE(scans_of_second_run, 10) << output;
}

}  // namespace
}  // namespace slammtt
