// slammtt-rplidar as a process against the emulator, through the code path of the robot:
// libserialport on a pseudo-terminal (this program runs under tests/support/pty/pty-run) and a
// TCP bridge; LCM inside a network namespace of its own. Scans, DTR and PWM motor control as
// the emulator sees them, unplug and replug, faults on a real link, and the clean stop on
// SIGTERM and SIGINT.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "drivers/rplidar/rplidar_emulator_server.h"
#include "rplidar_test_support.h"
#include "runtime/lcm_io.h"
#include "tests/support/child_process.h"

namespace slammtt {
namespace rplidar {
namespace {

using testing::ChildProcess;
using testing_support::CountBeamsDisagreeingWithRoom;
using testing_support::RecordingSink;

// Guards against a hang; never a measure of speed.
constexpr int kGuardMs = 30000;

// What the emulated device did, for the message of a failed expectation.
std::string DescribeDevice(const EmulatorServerStats& stats) {
  const RplidarDeviceStats& d = stats.device;
  std::string dtr = "unseen";
  if (d.host_dtr) dtr = *d.host_dtr ? "asserted" : "cleared";
  return "device: scanning " + std::to_string(d.scanning) + ", motor " +
         std::to_string(d.motor_running) + ", host DTR " + dtr + ", nodes " +
         std::to_string(d.nodes_sent) + ", capsules " + std::to_string(d.capsules_sent) +
         ", samples skipped " + std::to_string(d.samples_skipped) + ", overflow bytes " +
         std::to_string(stats.overflow_bytes) + ", last request " +
         std::to_string(d.last_request) + " (decimal)";
}

class RplidarProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NE(getenv("SLAMMTT_IN_PTY_NS"), nullptr) << "run under pty-run (ctest does)";
    lcm_ = OpenLcm(kDefaultLcmUrl);
    lcm_->subscribeFunction(
        "LASER_SCAN",
        +[](const lcm::ReceiveBuffer* buffer, const std::string& channel, RecordingSink* sink) {
          sink->Publish(channel, buffer->data, static_cast<int>(buffer->data_size));
        },
        &sink_);
    lcm_->subscribeFunction(
        "LIDAR_STATUS",
        +[](const lcm::ReceiveBuffer* buffer, const std::string& channel, RecordingSink* sink) {
          sink->Publish(channel, buffer->data, static_cast<int>(buffer->data_size));
        },
        &sink_);
    directory_ = testing::MakeTempDirectory("slammtt-rplidar-test");
  }
  void TearDown() override { testing::RemoveDirectoryTree(directory_); }

  std::unique_ptr<ChildProcess> StartDriver(const std::string& port, const std::string& mode) {
    return std::make_unique<ChildProcess>(std::vector<std::string>{
        std::string(SLAMMTT_BIN_DIR) + "/slammtt-rplidar", "--port", port, "--mode", mode,
        "--lcm-url", kDefaultLcmUrl});
  }

  // Handles LCM until `done()` or the guard expires; false on expiry.
  bool HandleUntil(const std::function<bool()>& done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(kGuardMs);
    while (!done()) {
      if (std::chrono::steady_clock::now() > end) return false;
      lcm_->handleTimeout(20);
    }
    return true;
  }

  // The emulated A2 with its accessory board (motor by PWM) on a TCP port, serving.
  static std::unique_ptr<RplidarEmulatorServer> StartTcpEmulatorWithAccessoryBoard() {
    EmulatorTransportOptions transport;
    transport.kind = EmulatorTransportOptions::Kind::kTcp;
    RplidarDeviceOptions device_options;
    device_options.accessory_board = true;
    auto emulator = std::make_unique<RplidarEmulatorServer>(device_options, transport);
    emulator->Start();
    return emulator;
  }

  bool WaitFor(const std::function<bool()>& done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(kGuardMs);
    while (!done()) {
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }

  void ExpectBeamsAgreeWithRoom() {
    const EmulatedRoom room = EmulatedRoom::Default();
    for (const auto& scan : sink_.scans()) {
      EXPECT_EQ(CountBeamsDisagreeingWithRoom(scan, room), 0) << "scan " << scan.sequence;
    }
  }

  std::unique_ptr<lcm::LCM> lcm_;
  RecordingSink sink_;
  std::string directory_;
};

TEST_F(RplidarProcessTest, ExpressOverLibserialportPtyThenCleanStopOnSigterm) {
  EmulatorTransportOptions transport;
  transport.link_path = directory_ + "/lidar";
  RplidarEmulatorServer emulator(RplidarDeviceOptions(), transport);
  emulator.Start();
  auto driver = StartDriver(transport.link_path, "express");
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 10; }));
  // The motor turns because the driver cleared DTR through libserialport (the shim carries
  // the line to the emulator).
  EXPECT_TRUE(emulator.stats().device.motor_running);
  EXPECT_EQ(emulator.stats().device.host_dtr, std::optional<bool>(false));
  const auto status = sink_.last_status();
  ASSERT_TRUE(status);
  EXPECT_EQ(status->endpoint.rfind("serial:" + transport.link_path + "=/dev/pts/", 0), 0u)
      << status->endpoint;
  EXPECT_EQ(status->scan_mode, "express");

  driver->Signal(SIGTERM);
  EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0));
  // The emulator saw the scan stopped and DTR asserted again: motor off.
  ASSERT_TRUE(WaitFor([&] { return !emulator.stats().device.motor_running; }));
  const auto device = emulator.stats().device;
  EXPECT_FALSE(device.scanning);
  EXPECT_EQ(device.requests.at(kStop), 2);
  EXPECT_EQ(device.requests.at(kExpressScan), 1);
  EXPECT_EQ(device.host_dtr, std::optional<bool>(true));
  HandleUntil([&] { return sink_.last_status() && sink_.last_status()->state == "stopped"; });
  EXPECT_EQ(sink_.last_status()->state, "stopped");
  ExpectBeamsAgreeWithRoom();
}

TEST_F(RplidarProcessTest, StandardOverTcpWithAccessoryBoardStopsOnSigint) {
  const auto emulator_owner = StartTcpEmulatorWithAccessoryBoard();
  RplidarEmulatorServer& emulator = *emulator_owner;
  auto driver = StartDriver(emulator.endpoint(), "standard");
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 10; }));
  EXPECT_EQ(emulator.stats().device.pwm, 660);
  EXPECT_TRUE(emulator.stats().device.motor_running);
  driver->Signal(SIGINT);
  EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0));
  ASSERT_TRUE(WaitFor([&] { return !emulator.stats().device.motor_running; }));
  const auto device = emulator.stats().device;
  EXPECT_FALSE(device.scanning);
  EXPECT_EQ(device.pwm, 0);
  EXPECT_EQ(device.requests.at(kScan), 1);
  ExpectBeamsAgreeWithRoom();
}

// Before: SIGTERM while the driver was in its reconnect backoff or waiting for a reply left the
// motor turning (3 of 3 runs): a muted device (no output, still hearing) kept PWM 660.
TEST_F(RplidarProcessTest, SigtermWhileReconnectingStopsTheMotor) {
  for (const int delay_ms : {0, 500}) {  // in the backoff; in the GET_INFO wait after it
    const auto emulator_owner = StartTcpEmulatorWithAccessoryBoard();
    RplidarEmulatorServer& emulator = *emulator_owner;
    auto driver = StartDriver(emulator.endpoint(), "express");
    ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 5; }));
    ASSERT_EQ(emulator.stats().device.pwm, 660);
    emulator.Mute(60000);
    ASSERT_TRUE(HandleUntil([&] {
      return sink_.last_status() && sink_.last_status()->state == "reconnecting";
    }));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    driver->Signal(SIGTERM);
    EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0)) << "delay " << delay_ms;
    // The emulator's thread handles what the driver sent on its own time.
    WaitFor([&] { return !emulator.stats().device.motor_running; });
    const auto device = emulator.stats().device;
    EXPECT_EQ(device.pwm, 0) << "delay " << delay_ms;
    EXPECT_FALSE(device.motor_running) << "delay " << delay_ms;
    sink_.Clear();
  }
}

TEST_F(RplidarProcessTest, UnpluggedPtyIsReopenedAtTheSameName) {
  EmulatorTransportOptions transport;
  transport.link_path = directory_ + "/lidar";
  RplidarEmulatorServer emulator(RplidarDeviceOptions(), transport);
  emulator.Start();
  auto driver = StartDriver(transport.link_path, "express");
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 3; }));
  emulator.Disconnect(1000);
  ASSERT_TRUE(HandleUntil([&] {
    const auto status = sink_.last_status();
    return status && status->reconnects >= 1 && status->state == "scanning";
  }));
  const size_t after_replug = sink_.scan_count();
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= after_replug + 5; }));
  bool reported = false;
  for (const auto& status : sink_.statuses()) {
    reported = reported || (status.state == "reconnecting" && !status.connected &&
                            status.last_error.find(transport.link_path) != std::string::npos);
  }
  EXPECT_TRUE(reported);
  EXPECT_EQ(emulator.stats().disconnects, 1);
  driver->Signal(SIGTERM);
  EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0));
  ExpectBeamsAgreeWithRoom();
}

TEST_F(RplidarProcessTest, TcpBridgeDropIsReconnected) {
  EmulatorTransportOptions transport;
  transport.kind = EmulatorTransportOptions::Kind::kTcp;
  RplidarEmulatorServer emulator(RplidarDeviceOptions(), transport);
  emulator.Start();
  auto driver = StartDriver(emulator.endpoint(), "express");
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 3; }));
  emulator.Disconnect(1000);
  ASSERT_TRUE(HandleUntil([&] {
    const auto status = sink_.last_status();
    return status && status->reconnects >= 1 && status->state == "scanning";
  }));
  const size_t after = sink_.scan_count();
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= after + 5; }));
  EXPECT_GE(emulator.stats().host_connections, 2);
  driver->Signal(SIGTERM);
  EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0));
  ExpectBeamsAgreeWithRoom();
}

TEST_F(RplidarProcessTest, FaultsOnARealLinkNeverBecomeBeams) {
  for (const char* mode : {"standard", "express"}) {
    EmulatorTransportOptions transport;
    transport.link_path = directory_ + "/lidar";
    RplidarEmulatorServer emulator(RplidarDeviceOptions(), transport);
    emulator.Start();
    auto driver = StartDriver(transport.link_path, mode);
    ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= 2; })) << mode;
    // Rounds are separated in the byte stream by half a revolution of clean packets (counted
    // by the emulator: scans seen here may have been sent before the last round).
    const auto packets = [&] {
      const RplidarDeviceStats device = emulator.stats().device;
      return device.nodes_sent + 32 * device.capsules_sent;
    };
    for (int round = 0; round < 5; ++round) {
      emulator.InjectGarbage(200);
      emulator.CorruptPackets(2);
      emulator.DropBytes(2);
      const int64_t sent = packets();
      const size_t count = sink_.scan_count();
      ASSERT_TRUE(HandleUntil([&] { return packets() >= sent + 200; })) << mode;
      ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= count + 2; })) << mode;
    }
    // LIDAR_STATUS comes once a second: wait for one that counts the faults.
    const bool express = std::string(mode) == "express";
    EXPECT_TRUE(HandleUntil([&] {
      const auto status = sink_.last_status();
      return status && status->resyncs >= 5;
    })) << mode;
    // Every damaged capsule here also lost a byte (a resync, not a checksum error), so only the
    // bound holds: never more checksum errors than capsules the emulator corrupted.
    if (express) {
      EXPECT_LE(sink_.last_status()->checksum_errors, emulator.stats().device.corrupted_packets);
    }
    EXPECT_EQ(sink_.last_status()->reconnects, 0)
        << mode << ": " << sink_.last_status()->last_error << "; "
        << DescribeDevice(emulator.stats());
    driver->Signal(SIGTERM);
    ASSERT_EQ(driver->Wait(kGuardMs), std::optional<int>(0)) << mode;
    ExpectBeamsAgreeWithRoom();
    HandleUntil([&] { return sink_.last_status() && sink_.last_status()->state == "stopped"; });
    sink_.Clear();
  }
}

TEST_F(RplidarProcessTest, EmulatorProgramWithScheduledFaultsAsStartedByHand) {
  const std::string link = directory_ + "/lidar";
  const std::string endpoint_file = directory_ + "/endpoint";
  ChildProcess emulator({std::string(SLAMMTT_BIN_DIR) + "/slammtt-rplidar-emulator", "--link",
                         link, "--endpoint-file", endpoint_file, "--health", "warning:0x7",
                         "--fault", "garbage@3.0:300", "--fault", "disconnect@4.0:1", "--quiet"});
  ASSERT_TRUE(WaitFor([&] { return access(endpoint_file.c_str(), R_OK) == 0; }));
  auto driver = StartDriver(link, "express");
  // The warning is reset once (the driver waits 2 s for the reboot); scans flow; the garbage
  // at 3 s is skipped; the unplug at 4 s is survived (the replugged device warns again and is
  // reset again: it had been good in between).
  ASSERT_TRUE(HandleUntil([&] {
    const auto status = sink_.last_status();
    return status && status->reconnects >= 1 && status->resyncs >= 1 &&
           status->state == "scanning" &&
           int{status->health} == int{slammtt_msgs::lidar_status_t::HEALTH_GOOD};
  }));
  const size_t after = sink_.scan_count();
  ASSERT_TRUE(HandleUntil([&] { return sink_.scan_count() >= after + 5; }));
  driver->Signal(SIGTERM);
  EXPECT_EQ(driver->Wait(kGuardMs), std::optional<int>(0));
  emulator.Signal(SIGTERM);
  EXPECT_EQ(emulator.Wait(kGuardMs), std::optional<int>(0));
  EXPECT_NE(access(link.c_str(), F_OK), 0) << "the emulator removes its link";
  unlink(endpoint_file.c_str());
  ExpectBeamsAgreeWithRoom();
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
