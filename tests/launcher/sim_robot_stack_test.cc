// The README's bring-up without the robot: slammtt-sim-robot (one simulated robot of the
// office scenario behind the P3-DX and RPLIDAR emulators), config/robot.yaml through
// slammtt-launch (the real drivers, segmenter and estimator; only the device paths, the command
// key and the office's laser mount changed), slammtt-teleop driving config/drive/office-room-a.txt
// (about 20 s: along the corridor, through door A, across room A), then slammtt-eval on the
// recorded log. Runs in a network namespace of its own.
#include <gtest/gtest.h>
#include <dirent.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;
using testing::RunProcess;

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string OnlyLog(const std::string& directory) {
  std::vector<std::string> names;
  if (DIR* dir = opendir(directory.c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.rfind("slammtt-", 0) == 0) names.push_back(name);
    }
    closedir(dir);
  }
  return names.size() == 1 ? directory + "/" + names[0] : "";
}

TEST(SimRobotStackTest, TeleopDrivesTheSimulatedRobotAndEvalScoresTheRecordedRun) {
  const std::string bin = SLAMMTT_BIN_DIR;
  const std::string source = SLAMMTT_SOURCE_DIR;
  const std::string directory = testing::MakeTempDirectory("sim-robot-stack-test");
  const std::string key = directory + "/command.key";
  ASSERT_EQ(RunProcess({bin + "/slammtt-command-key", "new", key}, directory).exit_code, 0);

  std::string config = ReadWholeFile(source + "/config/robot.yaml");
  config = Replace(config, "port: /dev/p3dx ", "port: tcp://127.0.0.1:5101 ");
  config = Replace(config, "port: /dev/rplidar", "port: tcp://127.0.0.1:5102");
  config = Replace(config, "# command_key_file: /etc/slammtt/command.key",
                   "command_key_file: " + key);
  // The office's laser sits 0.05 m ahead of the axle (config/scenarios/office.yaml): set in
  // the rplidar: section, it reaches the estimator on the driver's LASER_GEOMETRY.
  config = Replace(config, "mount_forward_m: 0.0 ", "mount_forward_m: 0.05");
  const std::string config_path = directory + "/robot-sim.yaml";
  std::ofstream(config_path) << config;

  ChildProcess robot({bin + "/slammtt-sim-robot", "--scenario", "office", "--seed", "1",
                      "--p3dx-tcp", "5101", "--rplidar-tcp", "5102"},
                     directory + "/robot.out", directory + "/robot.err");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto launcher = std::make_unique<ChildProcess>(
      std::vector<std::string>{bin + "/slammtt-launch", "--config", config_path},
      directory + "/launch.out", directory + "/launch.err", directory);
  std::this_thread::sleep_for(std::chrono::seconds(2));  // drivers connected, scans flowing
  const testing::ProcessResult teleop = RunProcess(
      {bin + "/slammtt-teleop", "--key", key, "--profile",
       source + "/config/drive/office-room-a.txt"},
      directory, 60000);
  EXPECT_EQ(teleop.exit_code, 0) << teleop.err;
  EXPECT_NE(teleop.err.find("robot stopped"), std::string::npos) << teleop.err;
  std::this_thread::sleep_for(std::chrono::seconds(1));
  launcher->Signal(SIGINT);
  const auto launcher_status = launcher->Wait(30000);
  const std::string launch_output =
      ReadWholeFile(directory + "/launch.out") + ReadWholeFile(directory + "/launch.err");
  ASSERT_TRUE(launcher_status.has_value()) << launch_output;
  EXPECT_EQ(*launcher_status, 0) << launch_output;
  EXPECT_EQ(launch_output.find("restarting"), std::string::npos) << launch_output;
  robot.Signal(SIGINT);
  EXPECT_EQ(robot.Wait(5000), 0);
  const std::string robot_err = ReadWholeFile(directory + "/robot.err");
  EXPECT_NE(robot_err.find(" 0 scans without truth, 0 bad scans"), std::string::npos)
      << robot_err;

  const std::string log = OnlyLog(directory + "/logs");
  ASSERT_FALSE(log.empty()) << launch_output;
  std::map<std::string, int> counts;
  std::vector<slammtt_msgs::odometry_t> odometry;
  std::vector<int64_t> truth_utimes;
  std::set<int64_t> pose_utimes;
  LogReader reader(log);
  while (auto event = reader.Next()) {
    ++counts[event->channel];
    const int size = static_cast<int>(event->data.size());
    if (event->channel == "GROUND_TRUTH") {
      slammtt_msgs::ground_truth_t truth;
      ASSERT_TRUE(Decode(event->data.data(), size, &truth));
      truth_utimes.push_back(truth.utime);
    } else if (event->channel == "POSE") {
      slammtt_msgs::pose_t pose;
      ASSERT_TRUE(Decode(event->data.data(), size, &pose));
      pose_utimes.insert(pose.utime);
    } else if (event->channel == "ODOMETRY") {
      odometry.emplace_back();
      ASSERT_TRUE(Decode(event->data.data(), size, &odometry.back()));
    }
  }
  // One GROUND_TRUTH for every LASER_SCAN the logger heard: the robot answers each scan at
  // once and outlives the logger (the last scan's truth may come as the logger stops).
  EXPECT_GE(counts["LASER_SCAN"], 150);
  EXPECT_LE(counts["GROUND_TRUTH"], counts["LASER_SCAN"]);
  EXPECT_GE(counts["GROUND_TRUTH"], counts["LASER_SCAN"] - 1);
  ASSERT_GE(odometry.size(), 2u);
  // The profile drives about 5 m; the base's own odometry saw the robot leave its start.
  const double moved_m = std::hypot(odometry.back().x_m - odometry.front().x_m,
                                    odometry.back().y_m - odometry.front().y_m);
  EXPECT_GT(moved_m, 1.0);

  const std::string report_path = directory + "/report.json";
  const testing::ProcessResult eval = RunProcess(
      {bin + "/slammtt-eval", log, "--config", config_path, "--json", report_path}, directory);
  ASSERT_EQ(eval.exit_code, 0) << eval.out << eval.err;
  std::cout << eval.out;  // the figures of this run, for the record
  const nlohmann::json report = nlohmann::json::parse(ReadWholeFile(report_path));
  const nlohmann::json& detail = report.at("detail");
  // Every ground-truth scan has the estimator's POSE of the same utime, but perhaps the last:
  // the logger may record the last scan's truth as the launcher stops the estimator (the race
  // of the counts above; seen once: 225 of 226 scans placed, the one without POSE the last).
  ASSERT_FALSE(truth_utimes.empty());
  const int64_t last_truth = *std::max_element(truth_utimes.begin(), truth_utimes.end());
  int without_pose = 0;
  for (int64_t utime : truth_utimes) {
    without_pose += utime != last_truth && pose_utimes.count(utime) == 0;
  }
  EXPECT_EQ(without_pose, 0);
  EXPECT_GE(detail.at("robot").at("scans").get<int>(),
            detail.at("input").at("ground_truth_scans").get<int>() - 1);
  // Measured on this test (office seed 1, 7 runs while other builds loaded the machine): ATE
  // RMSE 0.008-0.013 m, the base's odometry 0.001-0.002 m (the office's wheel slip is small).
  // The bound, about 2.5 times that, leaves room for scheduling delays (a late world step or a
  // late read makes the laser's pose or a scan's stamp a few milliseconds old: a few mm at
  // 0.3 m/s) and fails when the laser, the truth and the estimator disagree about the robot's
  // frame or clock (a scan stamped 0.1 s off its truth is 0.03 m; a laser angle of the wrong
  // sense or a truth in another frame, metres). It does not catch a laser mount left out of
  // the configuration: the same run with mount_forward_m 0 measured 0.027 m (and 0.025 m).
  EXPECT_LE(report.at("ate_rmse_m").get<double>(), 0.03) << eval.out;
  EXPECT_LE(report.at("odometry_ate_rmse_m").get<double>(), 0.03) << eval.out;
  // The walls of the corridor and of room A are mapped, each on a true surface.
  const nlohmann::json& lines = detail.at("map").at("lines");
  EXPECT_GE(lines.at("lines").get<int>(), 5) << eval.out;
  EXPECT_EQ(lines.at("matched").get<int>(), lines.at("lines").get<int>()) << eval.out;
  EXPECT_EQ(report.at("movers_in_static_map").get<int>(), 0) << eval.out;
  if (!::testing::Test::HasFailure()) testing::RemoveDirectoryTree(directory);
}

}  // namespace
}  // namespace slammtt
