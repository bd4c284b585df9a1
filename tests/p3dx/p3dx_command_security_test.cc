// Who can drive the robot, measured with a second host: this test's network namespace (from
// netns-run) is the robot's computer, running slammtt-p3dx against the emulated base; a second
// namespace joined to it by a veth pair (10.77.0.1 robot, 10.77.0.2 base station) stands in for
// another machine on the robot's LAN. From there the test sends what the attacker sent
// (40 unsigned VELOCITY_COMMAND at 10 Hz asking for 0.4 m/s, as raw LCM datagrams: unicast to
// the robot's address and multicast to the bus group) and runs slammtt-drive, the signing teleop.
// Each setup of docs/robot.md ("Who can drive the robot") gets its own test.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sched.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/command_signature.h"
#include "drivers/common/driver_clock.h"
#include "drivers/p3dx/p3dx_emulator.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;
using Clock = std::chrono::steady_clock;

constexpr char kRobotAddress[] = "10.77.0.1";
constexpr char kGroup[] = "239.255.76.67";
constexpr int kPort = 7667;
constexpr char kLoopbackBus[] = "udpm://239.255.76.67:7667?ttl=0";
constexpr char kLanBus[] = "udpm://239.255.76.67:7667?ttl=1";

// One LCM datagram as lcm_udpm.c sends a short message: magic "LC02", sequence number, the
// channel with its NUL, the encoded message (LCM UDP multicast protocol, "small messages").
std::vector<uint8_t> LcmDatagram(uint32_t sequence, const std::string& channel,
                                 const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> datagram = {0x4C, 0x43, 0x30, 0x32};
  for (int shift = 24; shift >= 0; shift -= 8) {
    datagram.push_back(static_cast<uint8_t>(sequence >> shift));
  }
  datagram.insert(datagram.end(), channel.begin(), channel.end());
  datagram.push_back(0);
  datagram.insert(datagram.end(), payload.begin(), payload.end());
  return datagram;
}

class CommandSecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = testing::MakeTempDirectory("p3dx-command-security-test");
    WriteNewCommandKeyFile(KeyPath(), NewCommandKey());
    key_ = LoadCommandKeyFile(KeyPath());
    // The base station's namespace: a process that only waits, whose network namespace the
    // veth peer goes into and every base-station program enters (nsenter).
    base_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"unshare", "--net", "--", "sleep", "600"},
        directory_ + "/base-namespace.log");
    ASSERT_TRUE(WaitForOwnNamespace(base_->pid()))
        << ReadWholeFile(directory_ + "/base-namespace.log");
    base_netns_ = "/proc/" + std::to_string(base_->pid()) + "/ns/net";
    ASSERT_EQ(Run("ip link add veth-robot type veth peer name veth-base netns " +
                  std::to_string(base_->pid())), 0);
    ASSERT_EQ(Run("ip addr add 10.77.0.1/24 dev veth-robot && ip link set veth-robot up"), 0);
    ASSERT_EQ(InBase("ip link set lo up && ip addr add 10.77.0.2/24 dev veth-base && "
                     "ip link set veth-base up && ip route add 224.0.0.0/4 dev veth-base"),
              0);
  }

  void TearDown() override {
    driver_.reset();
    stop_ = true;
    if (emulator_thread_.joinable()) emulator_thread_.join();
    base_.reset();
    if (HasFailure()) {
      std::cerr << "driver output:\n" << ReadWholeFile(directory_ + "/driver.log");
    } else {
      testing::RemoveDirectoryTree(directory_);
    }
  }

  std::string KeyPath() const { return directory_ + "/command.key"; }

  // The sleeper is in a namespace of its own once its /proc entry says so.
  static bool WaitForOwnNamespace(pid_t pid) {
    const std::string mine = ReadLink("/proc/self/ns/net");
    for (int k = 0; k < 500; ++k) {
      const std::string theirs = ReadLink("/proc/" + std::to_string(pid) + "/ns/net");
      if (!theirs.empty() && theirs != mine) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  static std::string ReadLink(const std::string& path) {
    char buffer[256];
    const ssize_t n = readlink(path.c_str(), buffer, sizeof buffer);
    return n > 0 ? std::string(buffer, static_cast<size_t>(n)) : std::string();
  }

  int Run(const std::string& command) {
    std::string output;
    const int status = testing::Shell(command, &output);
    if (status != 0) ADD_FAILURE() << command << ": " << output;
    return status;
  }
  int InBase(const std::string& command) {
    return Run("nsenter --net=" + base_netns_ + " sh -c '" + command + "'");
  }

  // The robot's computer: the bus route for the setup, the test's own bus (opened before the
  // driver, so that the driver's socket is the newest on the port and unicast reaches it, as
  // on a robot where the driver is the only LCM process), the emulated base, the driver.
  void StartRobot(const std::string& lcm_url, const std::string& p3dx_section) {
    lcm_url_ = lcm_url;
    lcm_ = OpenLcm(lcm_url);
    lcm_->subscribeFunction("BASE_STATUS", &CommandSecurityTest::OnStatus, this);
    P3dxEmulatorOptions emulator_options;
    emulator_options.use_pty = false;
    emulator_ = std::make_unique<P3dxEmulator>(emulator_options);
    emulator_thread_ = std::thread([this] { emulator_->Run([this] { return stop_.load(); }); });
    const std::string config = directory_ + "/robot.yaml";
    std::ofstream(config) << "lcm:\n  url: \"" << lcm_url << "\"\np3dx:\n  port: "
                          << emulator_->Endpoint() << "\n" << p3dx_section;
    driver_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{std::string(SLAMMTT_BIN_DIR) + "/slammtt-p3dx", "--config",
                                 config},
        directory_ + "/driver.log");
    ASSERT_TRUE(Pump(10.0, [&] { return !status_.empty() && status_.back().connected; }))
        << ReadWholeFile(directory_ + "/driver.log");
  }

  // Handles the bus for at most `seconds`, recording the base's top speed; true when `done`.
  bool Pump(double seconds, const std::function<bool()>& done) {
    const auto end = Clock::now() + std::chrono::milliseconds(static_cast<int>(seconds * 1000));
    while (Clock::now() < end) {
      lcm_->handleTimeout(10);
      top_speed_mmps_ = std::max(top_speed_mmps_, SpeedMmps());
      if (done()) return true;
    }
    return false;
  }
  void PumpFor(double seconds) { Pump(seconds, [] { return false; }); }

  double SpeedMmps() {
    return emulator_->WithModel([](P3dxRobotModel& m) {
      return std::max(std::abs(m.left_wheel_mmps()), std::abs(m.right_wheel_mmps()));
    });
  }
  double DistanceM() {
    return emulator_->WithModel(
        [](P3dxRobotModel& m) { return std::hypot(m.x_mm(), m.y_mm()) * 1e-3; });
  }

  // The attacker's 40 unsigned commands at 10 Hz for 0.4 m/s, as datagrams.
  static std::vector<std::vector<uint8_t>> UnsignedAttack() {
    std::vector<std::vector<uint8_t>> datagrams;
    for (uint32_t k = 0; k < 40; ++k) {
      slammtt_msgs::velocity_command_t command{};
      command.linear_mps = 0.4;
      datagrams.push_back(LcmDatagram(k, "VELOCITY_COMMAND", Encode(command)));
    }
    return datagrams;
  }

  // Sends `datagrams` 100 ms apart from the base station's namespace to address:7667 (ttl 1 for
  // multicast), while this process pumps the robot's bus. The sender is a forked child that
  // enters the other namespace (setns) and makes only system calls.
  void SendFromBaseStation(const std::vector<std::vector<uint8_t>>& datagrams,
                           const std::string& address) {
    const int netns = open(base_netns_.c_str(), O_RDONLY | O_CLOEXEC);
    ASSERT_GE(netns, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(kPort);
    ASSERT_EQ(inet_pton(AF_INET, address.c_str(), &to.sin_addr), 1);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      if (setns(netns, CLONE_NEWNET) != 0) _exit(2);
      const int fd = socket(AF_INET, SOCK_DGRAM, 0);
      const unsigned char ttl = 1;
      setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
      int failures = 0;
      for (const std::vector<uint8_t>& datagram : datagrams) {
        if (sendto(fd, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&to),
                   sizeof to) != static_cast<ssize_t>(datagram.size())) {
          ++failures;
        }
        usleep(100000);
      }
      _exit(failures == 0 ? 0 : 3);
    }
    close(netns);
    int status = -1;
    const auto give_up = Clock::now() + std::chrono::seconds(30);
    while (waitpid(pid, &status, WNOHANG) == 0 && Clock::now() < give_up) PumpFor(0.05);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "sender status " << status;
    PumpFor(1.5);  // the last datagram handled, one BASE_STATUS period
  }

  // slammtt-drive on the base station: signed commands on the LAN bus.
  void DriveFromBaseStation(double linear_mps, double seconds) {
    ChildProcess drive({"nsenter", "--net=" + base_netns_, "--",
                        std::string(SLAMMTT_BIN_DIR) + "/slammtt-drive", "--lcm-url", kLanBus,
                        "--key", KeyPath(), "--linear-mps", std::to_string(linear_mps),
                        "--duration-s", std::to_string(seconds)},
                       directory_ + "/drive.log");
    std::optional<int> status;
    const auto give_up = Clock::now() + std::chrono::seconds(30);
    while (!(status = drive.Wait(0)) && Clock::now() < give_up) PumpFor(0.05);
    ASSERT_EQ(status, 0) << ReadWholeFile(directory_ + "/drive.log");
    PumpFor(1.5);
  }

  const slammtt_msgs::base_status_t& LastStatus() const { return status_.back(); }

  static void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string&,
                       CommandSecurityTest* self) {
    slammtt_msgs::base_status_t message;
    if (Decode(buffer->data, static_cast<int>(buffer->data_size), &message)) {
      self->status_.push_back(message);
    }
  }

  std::string directory_;
  CommandKey key_{};
  std::unique_ptr<ChildProcess> base_;
  std::string base_netns_;
  std::string lcm_url_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<P3dxEmulator> emulator_;
  std::thread emulator_thread_;
  std::atomic<bool> stop_{false};
  std::unique_ptr<ChildProcess> driver_;
  std::vector<slammtt_msgs::base_status_t> status_;
  double top_speed_mmps_ = 0.0;
};

// The shipped setup: bus on ttl=0 with the group routed on the loopback interface (netns-run
// does what config/systemd/slammtt-lcm-route.service does), a key on the robot. Unicast from
// the LAN reaches the bus (LCM 1.3.1 binds 0.0.0.0:7667) and is refused for its missing tag;
// multicast from the LAN never reaches it (the group is joined on lo only), not even a key
// holder's.
TEST_F(CommandSecurityTest, LoopbackSetupNothingFromTheLanMovesTheRobot) {
  StartRobot(kLoopbackBus, "  command_key_file: " + KeyPath() + "\n");
  EXPECT_EQ(LastStatus().command_auth, "hmac-sha256");

  SendFromBaseStation(UnsignedAttack(), kRobotAddress);
  EXPECT_EQ(top_speed_mmps_, 0.0);
  EXPECT_EQ(LastStatus().commands_unauthenticated, 40);  // arrived, refused, counted

  SendFromBaseStation(UnsignedAttack(), kGroup);
  EXPECT_EQ(top_speed_mmps_, 0.0);
  EXPECT_EQ(LastStatus().commands_unauthenticated, 40);  // never arrived

  DriveFromBaseStation(0.3, 1.0);  // signed, but on the LAN's multicast
  EXPECT_EQ(top_speed_mmps_, 0.0);
  EXPECT_EQ(LastStatus().commands_accepted, 0);
  EXPECT_EQ(DistanceM(), 0.0);
  // Logged, rate-limited: 40 refusals are reported the 1st and the 10th time, two lines.
  const std::string log = ReadWholeFile(directory_ + "/driver.log");
  int refusal_lines = 0;
  for (size_t at = log.find("VELOCITY_COMMAND refused"); at != std::string::npos;
       at = log.find("VELOCITY_COMMAND refused", at + 1)) {
    ++refusal_lines;
  }
  EXPECT_EQ(refusal_lines, 2) << log;
  EXPECT_NE(log.find("(10 refused so far, counted in BASE_STATUS)"), std::string::npos) << log;
}

// The LAN setup: the bus on ttl=1 routed to the LAN interface, the key on the robot and on the
// base station. Unsigned unicast and multicast are refused; slammtt-drive with the key drives
// the robot; the same signed datagram played twice moves it once.
TEST_F(CommandSecurityTest, LanSetupOnlyTheKeyDrivesTheRobot) {
  ASSERT_EQ(Run("ip route replace 224.0.0.0/4 dev veth-robot"), 0);
  StartRobot(kLanBus, "  command_key_file: " + KeyPath() + "\n");

  SendFromBaseStation(UnsignedAttack(), kRobotAddress);
  SendFromBaseStation(UnsignedAttack(), kGroup);
  EXPECT_EQ(top_speed_mmps_, 0.0);
  EXPECT_EQ(LastStatus().commands_unauthenticated, 80);
  EXPECT_EQ(LastStatus().commands_accepted, 0);

  DriveFromBaseStation(0.3, 2.0);
  EXPECT_NEAR(top_speed_mmps_, 300.0, 1e-6);
  EXPECT_GE(LastStatus().commands_accepted, 15);  // 10 Hz for 2 s and a stop; some may be late
  EXPECT_GT(DistanceM(), 0.3);
  Pump(3.0, [&] { return SpeedMmps() == 0.0; });  // the final stop
  EXPECT_EQ(SpeedMmps(), 0.0);

  // A recorded signed command played back: refused after its first arrival.
  VelocityCommandSigner signer(key_, "VELOCITY_COMMAND", NewSenderId());
  slammtt_msgs::velocity_command_t command{};
  SystemDriverClock wall_clock;
  command.utime = wall_clock.NowUtime();
  command.linear_mps = 0.1;
  signer.Sign(&command);
  const std::vector<uint8_t> datagram = LcmDatagram(1, "VELOCITY_COMMAND", Encode(command));
  const int64_t accepted_before = LastStatus().commands_accepted;
  SendFromBaseStation({datagram, datagram, datagram}, kGroup);
  EXPECT_EQ(LastStatus().commands_accepted, accepted_before + 1);
  EXPECT_EQ(LastStatus().commands_replayed, 2);
  // Sent again 5 s after it was signed: outside the 1 s window.
  PumpFor(3.0);
  SendFromBaseStation({datagram}, kGroup);
  EXPECT_EQ(LastStatus().commands_stale, 1);
}

// The explicitly unauthenticated setup (command_authentication: none, bus on ttl=0): multicast
// from the LAN cannot reach the bus, but LCM 1.3.1 takes unicast datagrams to any address of
// the computer on its port, so the LAN can drive this robot unless a firewall stops UDP to the
// port (slammtt.service's IPAddressDeny=, docs/robot.md). This test pins that limit down.
TEST_F(CommandSecurityTest, UnauthenticatedLocalSetupIsOpenToUnicastFromTheLan) {
  StartRobot(kLoopbackBus, "  command_authentication: none\n");
  EXPECT_EQ(LastStatus().command_auth, "none (local only)");
  SendFromBaseStation(UnsignedAttack(), kGroup);
  EXPECT_EQ(top_speed_mmps_, 0.0);
  SendFromBaseStation(UnsignedAttack(), kRobotAddress);
  EXPECT_NEAR(top_speed_mmps_, 400.0, 1e-6);
  EXPECT_EQ(LastStatus().commands_accepted, 40);
}

// Unauthenticated commands on a bus that reaches the LAN: refused at start, one line.
TEST_F(CommandSecurityTest, UnauthenticatedCommandsOnALanBusAreRefusedAtStart) {
  const std::string config = directory_ + "/robot.yaml";
  std::ofstream(config) << "lcm:\n  url: \"" << kLanBus
                        << "\"\np3dx:\n  port: tcp://127.0.0.1:9\n  command_authentication: none\n";
  const testing::ProcessResult result = testing::RunProcess(
      {std::string(SLAMMTT_BIN_DIR) + "/slammtt-p3dx", "--config", config}, directory_, 10000);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("command_authentication: none is for a bus whose packets stay on "
                            "this computer"),
            std::string::npos)
      << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

}  // namespace
}  // namespace slammtt
