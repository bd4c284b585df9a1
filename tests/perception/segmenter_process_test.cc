// slammtt-segmenter as a process (label integration, run in a network namespace of its own by
// tests/support/netns-run): it segments scans published on the bus, survives garbage, stops
// cleanly on SIGTERM, and reports bad command lines and configurations in one line.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "tests/perception/synthetic_scan.h"

extern char** environ;

namespace slammtt {
namespace {

const std::string kProgram = std::string(SLAMMTT_BIN_DIR) + "/slammtt-segmenter";

std::string TempPath(const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/perception_" + std::to_string(getpid()) +
         "_" + name;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A child process with stdout and stderr in files; killed (by its pid) if still running at the end.
class Child {
 public:
  Child(const std::string& name, std::vector<std::string> args)
      : log_path_(TempPath("child_" + name)) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    std::remove(log_path_.c_str());
  }
  bool started() const { return pid_ > 0; }
  void Signal(int sig) { kill(pid_, sig); }
  // Waits up to timeout_s for the exit; the exit status, or -1 on timeout or a signal death.
  int Wait(double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(int(timeout_s * 1000));
    while (std::chrono::steady_clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return -1;
  }
  std::string Output() const { return ReadFile(log_path_); }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
  std::string log_path_;
};

slammtt_msgs::laser_scan_t Scan(int64_t sequence) {
  const testing_support::TestScan scan = testing_support::CastScan(
      {{2.0, 0.5, 0.2}, {-1.5, 2.5, 0.25}, {0.5, -3.0, 0.15}},
      testing_support::EvenAngles(0.0, 2.0 * M_PI, 400, true));
  slammtt_msgs::laser_scan_t msg;
  msg.utime = 1700000000000000 + sequence * 100000;
  msg.sequence = sequence;
  msg.scan_duration_us = 100000;
  msg.range_min_m = 0.15f;
  msg.range_max_m = 12.0f;
  msg.num_beams = static_cast<int32_t>(scan.size());
  msg.angle_rad = scan.angle_rad;
  msg.range_m = scan.range_m;
  msg.intensity.assign(scan.size(), 1.0f);
  msg.valid = scan.valid;
  return msg;
}

struct Received {
  std::vector<slammtt_msgs::features_t> features;
  std::vector<slammtt_msgs::stage_timing_t> timings;
};

TEST(SegmenterProcessTest, SegmentsScansOnTheBusAndStopsCleanly) {
  Child child("live", {kProgram, "--channel", "laser_scan=SCAN_UNDER_TEST"});
  ASSERT_TRUE(child.started());
  auto lcm = OpenLcm(kDefaultLcmUrl);
  Received received;
  lcm->subscribeFunction(
      "FEATURES",
      +[](const lcm::ReceiveBuffer* rbuf, const std::string&, Received* out) {
        slammtt_msgs::features_t msg;
        if (Decode(rbuf->data, static_cast<int>(rbuf->data_size), &msg)) {
          out->features.push_back(msg);
        }
      },
      &received);
  lcm->subscribeFunction(
      "STAGE_TIMING",
      +[](const lcm::ReceiveBuffer* rbuf, const std::string&, Received* out) {
        slammtt_msgs::stage_timing_t msg;
        if (Decode(rbuf->data, static_cast<int>(rbuf->data_size), &msg)) {
          out->timings.push_back(msg);
        }
      },
      &received);

  // Until the process has subscribed, scans go unheard: publish until the first answer (at most
  // 15 s, a bound for a loaded machine, not a measurement).
  int64_t sequence = 0;
  for (int attempt = 0; attempt < 300 && received.features.empty(); ++attempt) {
    const slammtt_msgs::laser_scan_t scan = Scan(sequence++);
    lcm->publish("SCAN_UNDER_TEST", &scan);
    lcm->handleTimeout(50);
  }
  ASSERT_FALSE(received.features.empty()) << child.Output();

  // Garbage on the scan channel, then ten more scans: every one is answered.
  const char garbage[7] = {1, 2, 3, 4, 5, 6, 7};
  lcm->publish("SCAN_UNDER_TEST", garbage, sizeof(garbage));
  const size_t before = received.features.size();
  const int64_t first_new = sequence;
  for (int i = 0; i < 10; ++i) {
    const slammtt_msgs::laser_scan_t scan = Scan(sequence++);
    lcm->publish("SCAN_UNDER_TEST", &scan);
    lcm->handleTimeout(20);
  }
  for (int i = 0; i < 200 && received.features.size() < before + 10; ++i) lcm->handleTimeout(50);
  ASSERT_EQ(received.features.size(), before + 10);
  for (size_t i = before; i < received.features.size(); ++i) {
    const slammtt_msgs::features_t& f = received.features[i];
    EXPECT_EQ(f.sequence, first_new + static_cast<int64_t>(i - before));
    EXPECT_EQ(f.utime, 1700000000000000 + f.sequence * 100000);
    EXPECT_EQ(f.num_features, 3);
  }
  ASSERT_FALSE(received.timings.empty());
  EXPECT_EQ(received.timings.back().stage, "segmenter");

  child.Signal(SIGTERM);
  EXPECT_EQ(child.Wait(10.0), 0) << child.Output();
  const std::string output = child.Output();
  EXPECT_NE(output.find("rejected message on SCAN_UNDER_TEST"), std::string::npos) << output;
  EXPECT_NE(output.find("1 messages rejected"), std::string::npos) << output;
}

TEST(SegmenterProcessTest, HelpAndBadInvocations) {
  {
    Child child("help", {kProgram, "--help"});
    EXPECT_EQ(child.Wait(10.0), 0);
    EXPECT_NE(child.Output().find("--config"), std::string::npos);
  }
  {
    Child child("badopt", {kProgram, "--no-such-option"});
    EXPECT_EQ(child.Wait(10.0), 2);
    EXPECT_NE(child.Output().find("no-such-option"), std::string::npos) << child.Output();
  }
  const std::string config = TempPath("bad.yaml");
  {
    std::ofstream out(config);
    out << "segmenter:\n  lambda_deg: 20\n  centre_rule: centroid\n";
  }
  {
    Child child("badconfig", {kProgram, "--config", config});
    EXPECT_EQ(child.Wait(10.0), 1);
    const std::string output = child.Output();
    EXPECT_NE(output.find("centre_rule"), std::string::npos) << output;
    EXPECT_NE(output.find("bad.yaml:3"), std::string::npos) << output;
  }
  std::remove(config.c_str());
}

}  // namespace
}  // namespace slammtt
