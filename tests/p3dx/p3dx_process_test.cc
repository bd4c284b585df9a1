// slammtt-p3dx as a process on an LCM bus, against the emulator (in this test's process) over
// TCP and over a pseudo-terminal opened through libserialport. Runs under netns-run (a network
// namespace of its own) and pty-run (libserialport can open the pty): see CMakeLists.txt.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/command_signature.h"
#include "drivers/common/driver_clock.h"
#include "drivers/p3dx/p3dx_commands.h"
#include "drivers/p3dx/p3dx_emulator.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;

namespace cmd = p3dx_command;
using Clock = std::chrono::steady_clock;

enum class Transport { kTcp, kPty };

class P3dxProcessTest : public ::testing::TestWithParam<Transport> {
 protected:
  void SetUp() override {
    directory_ = testing::MakeTempDirectory("p3dx-process-test");
    // The robot's command key, and a stack file naming it: only signed commands move the base.
    const CommandKey key = NewCommandKey();
    WriteNewCommandKeyFile(directory_ + "/command.key", key);
    std::ofstream(directory_ + "/stack.yaml")
        << "p3dx:\n  command_key_file: " << directory_ << "/command.key\n";
    signer_ = std::make_unique<VelocityCommandSigner>(key, "VELOCITY_COMMAND", NewSenderId());
    lcm_ = OpenLcm(kDefaultLcmUrl);
    lcm_->subscribeFunction("ODOMETRY", &P3dxProcessTest::OnOdometry, this);
    lcm_->subscribeFunction("BASE_STATUS", &P3dxProcessTest::OnStatus, this);
  }

  void TearDown() override {
    driver_.reset();
    stop_ = true;
    if (emulator_thread_.joinable()) emulator_thread_.join();
    if (HasFailure()) {
      std::cerr << "driver output:\n" << ReadWholeFile(directory_ + "/driver.log");
    } else {
      testing::RemoveDirectoryTree(directory_);
    }
  }

  void StartEmulator(std::vector<P3dxEmulatorFault> faults = {}) {
    P3dxEmulatorOptions options;
    options.use_pty = GetParam() == Transport::kPty;
    options.pty_link = directory_ + "/p3dx";
    options.faults = std::move(faults);
    emulator_ = std::make_unique<P3dxEmulator>(options);
    emulator_thread_ = std::thread([this] { emulator_->Run([this] { return stop_.load(); }); });
  }

  void StartDriver(std::vector<std::string> extra = {}) {
    std::vector<std::string> argv = {std::string(SLAMMTT_BIN_DIR) + "/slammtt-p3dx", "--config",
                                     directory_ + "/stack.yaml", "--port",
                                     emulator_->Endpoint()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    driver_ = std::make_unique<ChildProcess>(argv, directory_ + "/driver.log");
  }

  // Handles LCM for `seconds`, calling `each` about every 10 ms; stops early when it returns
  // true.
  bool PumpUntil(double seconds, const std::function<bool()>& done) {
    const auto end = Clock::now() + std::chrono::milliseconds(static_cast<int>(seconds * 1000));
    while (Clock::now() < end) {
      lcm_->handleTimeout(10);
      if (done()) return true;
    }
    return false;
  }

  void Command(double linear_mps, double angular_radps) {
    slammtt_msgs::velocity_command_t command{};
    command.utime = wall_clock_.NowUtime();
    command.linear_mps = linear_mps;
    command.angular_radps = angular_radps;
    signer_->Sign(&command);
    lcm_->publish("VELOCITY_COMMAND", &command);
    last_command_us_ = P3dxEmulator::NowUs();
  }

  // Commands at 10 Hz while pumping.
  std::function<bool()> Commanding(double linear, double angular, std::function<bool()> done) {
    auto next = std::make_shared<Clock::time_point>(Clock::now());
    return [=] {
      if (Clock::now() >= *next) {
        Command(linear, angular);
        *next += std::chrono::milliseconds(100);
      }
      return done ? done() : false;
    };
  }

  bool WaitConnected(double seconds = 10.0) {
    return PumpUntil(seconds, [&] { return !status_.empty() && status_.back().connected; });
  }

  std::vector<P3dxReceivedCommand> Received() {
    return emulator_->WithModel([](P3dxRobotModel& m) { return m.received(); });
  }
  bool RobotMoving() {
    return emulator_->WithModel([](P3dxRobotModel& m) { return m.moving(); });
  }

  static void OnOdometry(const lcm::ReceiveBuffer* buffer, const std::string&, P3dxProcessTest* self) {
    slammtt_msgs::odometry_t message;
    if (Decode(buffer->data, static_cast<int>(buffer->data_size), &message)) {
      self->odometry_.push_back(message);
    }
  }
  static void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string&, P3dxProcessTest* self) {
    slammtt_msgs::base_status_t message;
    if (Decode(buffer->data, static_cast<int>(buffer->data_size), &message)) {
      self->status_.push_back(message);
    }
  }

  std::string directory_;
  std::unique_ptr<VelocityCommandSigner> signer_;
  SystemDriverClock wall_clock_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<P3dxEmulator> emulator_;
  std::thread emulator_thread_;
  std::atomic<bool> stop_{false};
  std::unique_ptr<ChildProcess> driver_;
  std::vector<slammtt_msgs::odometry_t> odometry_;
  std::vector<slammtt_msgs::base_status_t> status_;
  int64_t last_command_us_ = 0;
};

TEST_P(P3dxProcessTest, ConnectsPublishesAndKeepsTheWatchdogFed) {
  StartEmulator();
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  EXPECT_EQ(status_.back().robot_subclass, "p3dx");
  const size_t before = odometry_.size();
  PumpUntil(2.0, [] { return false; });
  EXPECT_GE(odometry_.size() - before, 15u);  // SIPs at 10 Hz

  // 10 Hz commands for 3 s: longer than the firmware's 2 s watchdog.
  bool started = false;
  bool stopped_while_commanded = false;
  PumpUntil(3.0, Commanding(0.3, 0.0, [&] {
              const bool moving = RobotMoving();
              if (moving) started = true;
              if (started && !moving) stopped_while_commanded = true;
              return false;
            }));
  EXPECT_TRUE(started);
  EXPECT_FALSE(stopped_while_commanded);
  EXPECT_EQ(emulator_->WithModel([](P3dxRobotModel& m) { return m.watchdog_stops(); }), 0);
  ASSERT_FALSE(odometry_.empty());
  EXPECT_NEAR(odometry_.back().linear_velocity_mps, 0.3, 1e-9);
  EXPECT_GT(odometry_.back().x_m, 0.6);

  // Commands stop: the robot is told to stop after the command timeout (0.5 s).
  int64_t stopped_us = 0;
  ASSERT_TRUE(PumpUntil(3.0, [&] {
    if (!RobotMoving()) stopped_us = P3dxEmulator::NowUs();
    return stopped_us != 0;
  }));
  const double delay_s = (stopped_us - last_command_us_) * 1e-6;
  EXPECT_GE(delay_s, 0.45);
  EXPECT_LE(delay_s, 1.5);  // 0.5 s plus scheduling slack on a loaded machine
  PumpUntil(1.2, [] { return false; });
  ASSERT_FALSE(status_.empty());
  EXPECT_TRUE(status_.back().command_timeout_stop);
}

void ExpectStopAndClose(const std::vector<P3dxReceivedCommand>& received) {
  ASSERT_GE(received.size(), 3u);
  const size_t n = received.size();
  EXPECT_EQ(received[n - 3].command.number, cmd::kVel);
  EXPECT_EQ(received[n - 3].command.value, 0);
  EXPECT_EQ(received[n - 2].command.number, cmd::kRvel);
  EXPECT_EQ(received[n - 2].command.value, 0);
  EXPECT_EQ(received[n - 1].command.number, cmd::kClose);
  EXPECT_TRUE(received[n - 1].connected);
}

TEST_P(P3dxProcessTest, SigtermStopsTheRobotAndClosesTheSession) {
  StartEmulator();
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  PumpUntil(1.0, Commanding(0.2, 0.2, {}));
  ASSERT_TRUE(RobotMoving());
  driver_->Signal(SIGTERM);
  PumpUntil(0.2, [] { return false; });  // keep the bus drained meanwhile
  const auto status = driver_->Wait(5000);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 0);
  EXPECT_FALSE(RobotMoving());
  EXPECT_FALSE(emulator_->WithModel([](P3dxRobotModel& m) { return m.connected(); }));
  ExpectStopAndClose(Received());
  PumpUntil(0.3, [] { return false; });
  ASSERT_FALSE(status_.empty());
  EXPECT_EQ(status_.back().state, "stopped");
}

TEST_P(P3dxProcessTest, SigintStopsTheRobotAndClosesTheSession) {
  StartEmulator();
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  PumpUntil(0.5, Commanding(-0.2, 0.0, {}));
  driver_->Signal(SIGINT);
  const auto status = driver_->Wait(5000);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 0);
  EXPECT_FALSE(RobotMoving());
  ExpectStopAndClose(Received());
}

TEST_P(P3dxProcessTest, ReconnectsAfterTheDeviceIsUnplugged) {
  StartEmulator({ParseP3dxEmulatorFault("disconnect@2:1")});
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  bool saw_disconnected = false;
  ASSERT_TRUE(PumpUntil(15.0, [&] {
    if (!status_.empty() && !status_.back().connected) saw_disconnected = true;
    return saw_disconnected && status_.back().connected;
  }));
  EXPECT_EQ(status_.back().reconnects, 1);
  EXPECT_FALSE(status_.back().last_error.empty());
  if (GetParam() == Transport::kTcp) {
    EXPECT_EQ(emulator_->host_connections(), 2);  // the driver came back on a new connection
  }
  const size_t before = odometry_.size();
  PumpUntil(1.0, [] { return false; });
  EXPECT_GE(odometry_.size() - before, 7u);
}

// A robot that goes quiet but still hears, while the planner goes on commanding 0.3 m/s: the
// driver's resync must not keep it driving (SYNC0 is a keep-alive to its open session). Before:
// it drove on through every SYNC0 retry (issue 15: 3.9 s, 0.84 m).
TEST_P(P3dxProcessTest, AQuietRobotIsStoppedWhenItsLinkIsGivenUp) {
  StartEmulator();
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  PumpUntil(1.0, Commanding(0.3, 0.0, {}));
  ASSERT_TRUE(RobotMoving());
  const int64_t quiet_from = P3dxEmulator::NowUs();
  emulator_->WithModel([](P3dxRobotModel& m) {
    m.MuteFor(15000000, P3dxEmulator::NowUs());
    return 0;
  });
  int64_t stopped_us = 0;
  PumpUntil(8.0, Commanding(0.3, 0.0, [&] {
              if (stopped_us == 0 && !RobotMoving()) stopped_us = P3dxEmulator::NowUs();
              return false;
            }));
  ASSERT_NE(stopped_us, 0) << "still moving 8 s after the robot went quiet";
  // The 1 s SIP timeout plus scheduling slack; the firmware's own watchdog (2 s after the last
  // byte it heard) never had to act.
  EXPECT_LE((stopped_us - quiet_from) * 1e-6, 1.6);
  EXPECT_EQ(emulator_->WithModel([](P3dxRobotModel& m) { return m.watchdog_stops(); }), 0);
}

TEST_P(P3dxProcessTest, DamagedPacketsNeverBecomeOdometry) {
  // The robot stands still, so every ODOMETRY must be exactly zero: any pose or speed that is
  // not came from a damaged packet.
  StartEmulator({ParseP3dxEmulatorFault("garbage@1:300"), ParseP3dxEmulatorFault("bad-checksum@1.5:3"),
                 ParseP3dxEmulatorFault("short@2:2"), ParseP3dxEmulatorFault("truncate@2.5:2"),
                 ParseP3dxEmulatorFault("drop@3:5"), ParseP3dxEmulatorFault("silence@3.5:1.5"),
                 ParseP3dxEmulatorFault("bumper@5.5:3,0"), ParseP3dxEmulatorFault("stall@6:0,1")});
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  PumpUntil(8.0, [] { return false; });
  ASSERT_FALSE(status_.empty());
  const auto& last = status_.back();
  EXPECT_TRUE(last.connected);
  EXPECT_GE(last.checksum_errors, 3);
  EXPECT_GE(last.short_packets, 2);
  EXPECT_EQ(last.reconnects, 1);  // the silence outlasted the 1 s SIP timeout
  EXPECT_EQ(last.bumpers, 3);
  EXPECT_FALSE(last.left_wheel_stall);
  EXPECT_TRUE(last.right_wheel_stall);
  ASSERT_GT(odometry_.size(), 40u);
  for (const auto& o : odometry_) {
    ASSERT_EQ(o.x_m, 0.0);
    ASSERT_EQ(o.y_m, 0.0);
    ASSERT_EQ(o.heading_rad, 0.0);
    ASSERT_EQ(o.linear_velocity_mps, 0.0);
    ASSERT_EQ(o.angular_velocity_radps, 0.0);
  }
}

// Bytes on VELOCITY_COMMAND that are no velocity_command_t are skipped and counted by the bus
// (runtime/bus.h), not a crash: the driver goes on and the next signed command drives the base.
TEST_P(P3dxProcessTest, UndecodableCommandsAreCountedAndSkipped) {
  StartEmulator();
  StartDriver();
  ASSERT_TRUE(WaitConnected());
  const char garbage[5] = {1, 2, 3, 4, 5};
  lcm_->publish("VELOCITY_COMMAND", garbage, sizeof garbage);
  slammtt_msgs::odometry_t wrong_type{};
  lcm_->publish("VELOCITY_COMMAND", &wrong_type);
  ASSERT_TRUE(PumpUntil(5.0, Commanding(0.2, 0.0, [&] { return RobotMoving(); })));
  ASSERT_TRUE(driver_->running());
  driver_->Signal(SIGTERM);
  PumpUntil(0.2, [] { return false; });
  const auto status = driver_->Wait(5000);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 0);
  const std::string log = ReadWholeFile(directory_ + "/driver.log");
  EXPECT_NE(log.find("VELOCITY_COMMAND: undecodable message skipped (1 so far)"),
            std::string::npos)
      << log;
}

INSTANTIATE_TEST_SUITE_P(Transports, P3dxProcessTest,
                         ::testing::Values(Transport::kTcp, Transport::kPty),
                         [](const ::testing::TestParamInfo<Transport>& param_info) {
                           return param_info.param == Transport::kTcp ? std::string("Tcp") : std::string("Pty");
                         });

TEST(P3dxProcessOptionsTest, BadOptionsAreOneLineErrors) {
  const std::string directory = testing::MakeTempDirectory("p3dx-options-test");
  const std::string bin = std::string(SLAMMTT_BIN_DIR) + "/slammtt-p3dx";
  {
    ChildProcess p({bin, "--port", "ttyUSB0"}, directory + "/a.log");
    EXPECT_EQ(p.Wait(5000), 2);
  }
  const std::string config = directory + "/stack.yaml";
  {
    std::ofstream(config) << "p3dx:\n  port: /dev/ttyUSB0\n  max_linear_mps: 0.4\n  speed: 3\n";
    ChildProcess p({bin, "--config", config}, directory + "/b.log");
    EXPECT_EQ(p.Wait(5000), 1);
  }
  {
    std::ofstream(config) << "p3dx:\n  port: /dev/ttyUSB0\n  pulse_interval_s: 2.5\n";
    ChildProcess p({bin, "--config", config}, directory + "/c.log");
    EXPECT_EQ(p.Wait(5000), 1);
  }
  const std::string a = ReadWholeFile(directory + "/a.log");
  const std::string b = ReadWholeFile(directory + "/b.log");
  const std::string c = ReadWholeFile(directory + "/c.log");
  EXPECT_NE(a.find("ttyUSB0"), std::string::npos) << a;
  EXPECT_NE(b.find("p3dx.speed"), std::string::npos) << b;
  EXPECT_NE(c.find("pulse_interval_s"), std::string::npos) << c;
  for (const std::string* text : {&a, &b, &c}) {
    EXPECT_EQ(std::count(text->begin(), text->end(), '\n'), 1) << *text;
  }
  if (!::testing::Test::HasFailure()) testing::RemoveDirectoryTree(directory);
}

}  // namespace
}  // namespace slammtt
