// The robot's stack exactly as config/robot.yaml starts it, with the two device emulators
// standing in for the base and the laser on TCP ports (the only change to the file: the two
// device paths), as docs/robot.md shows. Runs in a network namespace of its own.
#include <gtest/gtest.h>
#include <dirent.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <map>
#include <string>
#include <thread>

#include "child_process.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"

namespace slammtt {
namespace {

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

TEST(RobotStackTest, RobotYamlRunsTheWholeStackAgainstTheEmulators) {
  const std::string directory = MakeTempDirectory("robot-stack-test");
  const std::string bin = SLAMMTT_BIN_DIR;
  std::string config = ReadWholeFile(std::string(SLAMMTT_SOURCE_DIR) + "/config/robot.yaml");
  ASSERT_FALSE(config.empty());
  config = Replace(config, "port: /dev/p3dx ", "port: tcp://127.0.0.1:5101 ");
  config = Replace(config, "port: /dev/rplidar", "port: tcp://127.0.0.1:5102");
  const std::string config_path = directory + "/robot-emulated.yaml";
  std::ofstream(config_path) << config;

  ChildProcess base({bin + "/slammtt-p3dx-emulator", "--tcp", "5101"}, directory + "/base.log");
  ChildProcess laser({bin + "/slammtt-rplidar-emulator", "--tcp", "5102"}, directory + "/laser.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::string out = directory + "/launch.out";
  const std::string err = directory + "/launch.err";
  ChildProcess launcher({bin + "/slammtt-launch", "--config", config_path}, out, err, directory);
  std::this_thread::sleep_for(std::chrono::seconds(5));
  launcher.Signal(SIGINT);
  const auto status = launcher.Wait(30000);
  const std::string output = ReadWholeFile(out) + ReadWholeFile(err);
  ASSERT_TRUE(status.has_value()) << output;
  EXPECT_EQ(*status, 0) << output;
  for (const char* name : {"logger", "p3dx", "rplidar", "segmenter", "estimator"}) {
    EXPECT_NE(output.find(std::string(name) + " stopped (exited with status 0)"), std::string::npos)
        << name << "\n" << output;
  }
  EXPECT_EQ(output.find("restarting"), std::string::npos) << output;
  EXPECT_NE(output.find("p3dx      | slammtt-p3dx: info: robot stopped and session closed"),
            std::string::npos) << output;

  const std::vector<std::string> logs = FilesIn(directory + "/logs");
  ASSERT_EQ(logs.size(), 1u) << output;
  EXPECT_EQ(logs[0].rfind("slammtt-", 0), 0u);
  LogReader reader(directory + "/logs/" + logs[0]);
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
  base.Signal(SIGINT);
  laser.Signal(SIGINT);
  EXPECT_EQ(base.Wait(5000), 0);
  EXPECT_EQ(laser.Wait(5000), 0);
  if (!::testing::Test::HasFailure()) RemoveDirectoryTree(directory);
}

}  // namespace
}  // namespace slammtt
