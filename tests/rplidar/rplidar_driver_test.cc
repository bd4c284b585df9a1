// The driver's whole lifecycle against the device model, in virtual time: deterministic and
// fast. Every fault of the issue: garbage, bad checksums and lost sync bits, dropped bytes,
// silence, unplug and replug, health error (refused with its code) and warning (reset once),
// and the clean stop.
#include "drivers/rplidar/rplidar_driver.h"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <stdexcept>

#include "rplidar_test_support.h"

namespace slammtt {
namespace rplidar {
namespace {

using testing_support::CountBeamsDisagreeingWithRoom;
using testing_support::kUtimeBase;
using testing_support::RecordingSink;
using testing_support::VirtualClock;
using testing_support::VirtualLink;

struct Rig {
  explicit Rig(RplidarDeviceOptions device_options = RplidarDeviceOptions(),
               ScanMode mode = ScanMode::kExpress)
      : device(device_options), model(device_options), sink(&clock) {
    options.port = "virtual";
    options.scan_mode = mode;
  }

  // Runs the driver until `done()`; `hook()` runs at every check (fault injection).
  void Run(const std::function<bool()>& done, const std::function<void()>& hook = [] {}) {
    RplidarDriver driver(
        options,
        [this]() -> std::unique_ptr<ByteStream> {
          open_times_us.push_back(clock.now_us_);
          if (unplugged) throw LinkError("virtual:rplidar: no such device");
          return std::make_unique<VirtualLink>(&model, &clock, &unplugged);
        },
        &clock, &sink, "LASER_SCAN", "LIDAR_STATUS", "LASER_GEOMETRY");
    const int64_t limit_us = clock.now_us_ + 120 * 1000000LL;  // a broken driver cannot spin forever
    driver.Run([&] {
      hook();
      return done() || clock.now_us_ > limit_us;
    });
    final_status = driver.status();
  }

  bool AnyStatus(const std::function<bool(const slammtt_msgs::lidar_status_t&)>& test) const {
    for (const auto& status : sink.statuses()) {
      if (test(status)) return true;
    }
    return false;
  }

  RplidarDeviceOptions device;
  RplidarDeviceModel model;
  VirtualClock clock;
  RecordingSink sink;
  RplidarDriverOptions options;
  bool unplugged = false;
  std::vector<int64_t> open_times_us;
  slammtt_msgs::lidar_status_t final_status;
};

void ExpectScansMatchTheRoom(const Rig& rig, int min_beams, int max_beams) {
  const auto scans = rig.sink.scans();
  ASSERT_FALSE(scans.empty());
  int64_t previous_utime = 0;
  for (size_t i = 0; i < scans.size(); ++i) {
    const auto& scan = scans[i];
    EXPECT_EQ(scan.sequence, static_cast<int64_t>(i));
    EXPECT_GE(scan.num_beams, min_beams) << "scan " << i;
    EXPECT_LE(scan.num_beams, max_beams) << "scan " << i;
    EXPECT_EQ(scan.angle_rad.size(), static_cast<size_t>(scan.num_beams));
    EXPECT_EQ(scan.valid.size(), static_cast<size_t>(scan.num_beams));
    EXPECT_EQ(CountBeamsDisagreeingWithRoom(scan, EmulatedRoom::Default()), 0) << "scan " << i;
    EXPECT_GT(scan.utime, previous_utime);
    previous_utime = scan.utime;
  }
}

TEST(RplidarDriverTest, ExpressScansMatchTheRoomAndStatusDescribesTheDevice) {
  Rig rig;
  rig.Run([&] { return rig.sink.scan_count() >= 20; });
  // 4000 samples/s at 10 Hz: 400 beams per revolution.
  ExpectScansMatchTheRoom(rig, 398, 402);
  const auto scans = rig.sink.scans();
  int no_return = 0;
  for (const auto& scan : scans) {
    for (int8_t valid : scan.valid) no_return += valid ? 0 : 1;
  }
  EXPECT_GT(no_return, 0) << "the dark pane gives beams without a return";
  const auto status = rig.sink.last_status();
  ASSERT_TRUE(status);
  EXPECT_EQ(status->model, 0x28);
  EXPECT_EQ(status->firmware_major, 1);
  EXPECT_EQ(status->firmware_minor, 29);
  EXPECT_EQ(status->hardware, 7);
  EXPECT_EQ(status->serial_number, "5EA13C001D429B278064C31107F2382A");
  EXPECT_EQ(int{status->health}, int{slammtt_msgs::lidar_status_t::HEALTH_GOOD});
  EXPECT_EQ(status->scan_mode, "express");
  EXPECT_TRUE(rig.AnyStatus([](const auto& s) { return s.state == "scanning"; }));
  EXPECT_EQ(rig.final_status.state, "stopped");
  EXPECT_EQ(rig.final_status.resyncs, 0);
  EXPECT_EQ(rig.final_status.checksum_errors, 0);
  EXPECT_EQ(rig.final_status.reconnects, 0);
  double last_scanning_rate_hz = 0.0;
  for (const auto& s : rig.sink.statuses()) {
    if (s.state == "scanning") last_scanning_rate_hz = s.scan_rate_hz;
  }
  EXPECT_NEAR(last_scanning_rate_hz, 10.0, 0.2);  // virtual time: the exact rotation
}

// The mount of the rplidar: section travels on LASER_GEOMETRY, right after every LIDAR_STATUS
// (at start, about once a second, on every change), for the estimator (docs/estimator.md).
TEST(RplidarDriverTest, EveryStatusIsFollowedByTheLasersGeometry) {
  Rig rig;
  rig.options.mount_forward_m = 0.12;
  rig.options.mount_left_m = -0.03;
  rig.options.mount_yaw_deg = 90.0;
  rig.options.beams.range_max_m = 16.0;
  rig.Run([&] { return rig.sink.scan_count() >= 25; });
  const std::vector<std::string> channels = rig.sink.channels();
  const auto geometries = rig.sink.geometries();
  ASSERT_GE(geometries.size(), 3u);  // connecting, scanning, at least one periodic
  EXPECT_EQ(geometries.size(), rig.sink.statuses().size());
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] == "LIDAR_STATUS") {
      ASSERT_LT(k + 1, channels.size());
      EXPECT_EQ(channels[k + 1], "LASER_GEOMETRY") << k;
    }
  }
  const auto statuses = rig.sink.statuses();
  for (size_t k = 0; k < geometries.size(); ++k) {
    const slammtt_msgs::laser_geometry_t& g = geometries[k];
    EXPECT_EQ(g.utime, statuses[k].utime);
    EXPECT_EQ(g.mount_forward_m, 0.12);
    EXPECT_EQ(g.mount_left_m, -0.03);
    EXPECT_EQ(g.mount_yaw_rad, 90.0 * M_PI / 180.0);
    EXPECT_EQ(g.view_start_rad, -M_PI);
    EXPECT_EQ(g.view_end_rad, M_PI);
    EXPECT_EQ(g.range_min_m, 0.15);
    EXPECT_EQ(g.range_max_m, 16.0);
    EXPECT_EQ(g.source, "slammtt-rplidar, rplidar: section");
  }
}

TEST(RplidarDriverTest, StandardScansMatchTheRoom) {
  Rig rig(RplidarDeviceOptions(), ScanMode::kStandard);
  rig.Run([&] { return rig.sink.scan_count() >= 20; });
  // 2000 samples/s at 10 Hz: 200 beams per revolution.
  ExpectScansMatchTheRoom(rig, 199, 201);
  EXPECT_EQ(rig.final_status.scan_mode, "standard");
  EXPECT_EQ(rig.model.stats().requests.count(kScan), 1u);
}

TEST(RplidarDriverTest, UtimeIsTheArrivalOfTheFirstSample) {
  for (ScanMode mode : {ScanMode::kStandard, ScanMode::kExpress}) {
    Rig rig(RplidarDeviceOptions(), mode);
    rig.Run([&] { return rig.sink.scan_count() >= 10; });
    const auto scans = rig.sink.scans();
    const auto published = rig.sink.publish_utimes();
    for (size_t i = 1; i < scans.size(); ++i) {
      // Scan i-1 is published once the first sample of scan i is decoded: standard, when the
      // node after it has arrived (0.5 ms later); express, when the capsule after the one
      // holding it has arrived (8 ms later). Scan i's utime is when that first sample arrived.
      const int64_t decode_lag_us = mode == ScanMode::kExpress ? 8000 : 500;
      EXPECT_LE(scans[i].utime, published[i - 1]);
      EXPECT_GE(scans[i].utime, published[i - 1] - decode_lag_us - 500) << ScanModeName(mode);
      // and a revolution lasts 100 ms of device time, give or take the arrival granularity
      // (a node, or a capsule of 32 samples = 8 ms).
      EXPECT_NEAR(static_cast<double>(scans[i].utime - scans[i - 1].utime), 100000.0,
                  static_cast<double>(decode_lag_us + 1000));
      EXPECT_NEAR(static_cast<double>(scans[i].scan_duration_us), 100000.0, 10000.0);
      EXPECT_GT(scans[i].utime, kUtimeBase);
    }
  }
}

TEST(RplidarDriverTest, HealthErrorIsRefusedWithItsCodeAfterOneReset) {
  RplidarDeviceOptions device;
  device.health = {HealthStatus::kError, 0x1234};
  device.health_persists_after_reset = true;
  Rig rig(device);
  rig.options.reconnect_max_ms = 1000;
  const int64_t end = rig.clock.now_us_ + 10 * 1000000LL;
  rig.Run([&] { return rig.clock.now_us_ > end; });
  const RplidarDeviceStats& stats = rig.model.stats();
  EXPECT_EQ(stats.resets, 1) << "one reset per health problem, not one per retry";
  EXPECT_EQ(stats.requests.count(kScan), 0u);
  EXPECT_EQ(stats.requests.count(kExpressScan), 0u);
  EXPECT_GE(stats.requests.at(kGetHealth), 5) << "health is checked again after each backoff";
  EXPECT_FALSE(stats.motor_running) << "the motor never started";
  EXPECT_EQ(rig.sink.scan_count(), 0u);
  EXPECT_TRUE(rig.AnyStatus([](const auto& s) {
    return s.state == "health_error" && int{s.health} == int{slammtt_msgs::lidar_status_t::HEALTH_ERROR} &&
           s.health_error_code == 0x1234 &&
           s.last_error.find("code 0x1234") != std::string::npos &&
           s.last_error.find("refusing to scan") != std::string::npos;
  }));
}

TEST(RplidarDriverTest, HealthErrorClearedByTheResetScans) {
  RplidarDeviceOptions device;
  device.health = {HealthStatus::kError, 0x0042};
  Rig rig(device);
  rig.Run([&] { return rig.sink.scan_count() >= 3; });
  EXPECT_EQ(rig.model.stats().resets, 1);
  EXPECT_EQ(int{rig.final_status.health}, int{slammtt_msgs::lidar_status_t::HEALTH_GOOD});
  ExpectScansMatchTheRoom(rig, 398, 402);
}

TEST(RplidarDriverTest, HealthWarningResetsOnceAndScans) {
  for (bool persists : {false, true}) {
    RplidarDeviceOptions device;
    device.health = {HealthStatus::kWarning, 0x0007};
    device.health_persists_after_reset = persists;
    Rig rig(device);
    rig.Run([&] { return rig.sink.scan_count() >= 3; });
    EXPECT_EQ(rig.model.stats().resets, 1) << "persists " << persists;
    EXPECT_EQ(int{rig.final_status.health}, persists ? int{slammtt_msgs::lidar_status_t::HEALTH_WARNING}
                                                : int{slammtt_msgs::lidar_status_t::HEALTH_GOOD});
    EXPECT_GE(rig.sink.scan_count(), 3u);
  }
}

// Injects a packet fault every `every` scans, `times` times, once scanning.
void RunWithFault(Rig& rig, int times, const std::function<void(RplidarDeviceModel&)>& fault) {
  int injected = 0;
  size_t last_count = 0;
  rig.Run([&] { return injected >= times && rig.sink.scan_count() >= last_count + 3; },
          [&] {
            const size_t count = rig.sink.scan_count();
            if (injected < times && count >= 2 && count >= last_count + 2) {
              fault(rig.model);
              ++injected;
              last_count = count;
            }
          });
  EXPECT_EQ(injected, times);
}

TEST(RplidarDriverTest, GarbageBytesAreSkippedWithAResyncNeverTurnedIntoBeams) {
  for (ScanMode mode : {ScanMode::kStandard, ScanMode::kExpress}) {
    Rig rig(RplidarDeviceOptions(), mode);
    RunWithFault(rig, 10, [](RplidarDeviceModel& model) { model.InjectGarbage(300); });
    EXPECT_EQ(rig.model.stats().garbage_bytes, 3000);
    EXPECT_GE(rig.final_status.resyncs, 10) << ScanModeName(mode);
    EXPECT_EQ(rig.final_status.reconnects, 0);
    ExpectScansMatchTheRoom(rig, mode == ScanMode::kExpress ? 300 : 150,
                            mode == ScanMode::kExpress ? 402 : 201);
  }
}

TEST(RplidarDriverTest, BadChecksumsAndLostSyncBitsAreSkippedAndCounted) {
  for (ScanMode mode : {ScanMode::kStandard, ScanMode::kExpress}) {
    Rig rig(RplidarDeviceOptions(), mode);
    RunWithFault(rig, 10, [](RplidarDeviceModel& model) { model.CorruptPackets(1); });
    EXPECT_EQ(rig.model.stats().corrupted_packets, 10);
    if (mode == ScanMode::kExpress) {
      EXPECT_EQ(rig.final_status.checksum_errors, 10);  // the corrupted capsules, no false syncs
    }
    EXPECT_GE(rig.final_status.resyncs, 10) << ScanModeName(mode);
    ExpectScansMatchTheRoom(rig, mode == ScanMode::kExpress ? 300 : 150,
                            mode == ScanMode::kExpress ? 402 : 201);
  }
}

TEST(RplidarDriverTest, DroppedBytesAreSkippedWithAResync) {
  for (ScanMode mode : {ScanMode::kStandard, ScanMode::kExpress}) {
    Rig rig(RplidarDeviceOptions(), mode);
    RunWithFault(rig, 10, [](RplidarDeviceModel& model) { model.DropBytes(1); });
    EXPECT_EQ(rig.model.stats().dropped_bytes, 10);
    EXPECT_GE(rig.final_status.resyncs, 10) << ScanModeName(mode);
    ExpectScansMatchTheRoom(rig, mode == ScanMode::kExpress ? 300 : 150,
                            mode == ScanMode::kExpress ? 402 : 201);
  }
}

TEST(RplidarDriverTest, SilentDeviceIsReportedAndReopened) {
  Rig rig;
  bool silenced = false;
  int64_t silence_end = 0;
  size_t scans_at_silence = 0;
  rig.Run(
      [&] { return silenced && rig.clock.now_us_ > silence_end && rig.sink.scan_count() >= scans_at_silence + 5; },
      [&] {
        if (!silenced && rig.sink.scan_count() >= 3) {
          rig.model.Silence(3000000, rig.clock.now_us_);
          silence_end = rig.clock.now_us_ + 3000000;
          scans_at_silence = rig.sink.scan_count();
          silenced = true;
        }
      });
  EXPECT_GE(rig.final_status.reconnects, 1);
  EXPECT_TRUE(rig.AnyStatus([](const auto& s) {
    return s.state == "reconnecting" && s.last_error.find("no valid scan data for 1000 ms") !=
                                            std::string::npos;
  }));
  ExpectScansMatchTheRoom(rig, 398, 402);
}

TEST(RplidarDriverTest, UnpluggedDeviceIsReopenedWithBackoff) {
  Rig rig;
  bool pulled = false;
  bool replugged = false;
  int64_t replug_at = 0;
  size_t scans_at_replug = 0;
  rig.Run([&] { return replugged && rig.sink.scan_count() >= scans_at_replug + 5; },
          [&] {
            if (!pulled && rig.sink.scan_count() >= 3) {
              rig.unplugged = true;
              rig.model.PowerCycle(rig.clock.now_us_);
              replug_at = rig.clock.now_us_ + 2000000;
              pulled = true;
            }
            if (pulled && !replugged && rig.clock.now_us_ >= replug_at) {
              rig.unplugged = false;
              replugged = true;
              scans_at_replug = rig.sink.scan_count();
            }
          });
  // First open, then reopen attempts 200, 400, 800 ms apart while unplugged (plus the time the
  // failing attempt itself took, none here), then the one that works.
  ASSERT_GE(rig.open_times_us.size(), 5u);
  EXPECT_EQ(rig.open_times_us[2] - rig.open_times_us[1], 400000);
  EXPECT_EQ(rig.open_times_us[3] - rig.open_times_us[2], 800000);
  EXPECT_GE(rig.final_status.reconnects, 4);
  EXPECT_TRUE(rig.AnyStatus([](const auto& s) {
    return s.state == "reconnecting" && !s.connected &&
           s.last_error.find("no such device") != std::string::npos;
  }));
  EXPECT_EQ(rig.model.stats().resets, 0);
  ExpectScansMatchTheRoom(rig, 398, 402);
}

TEST(RplidarDriverTest, StopEndsTheScanAndStopsTheMotor) {
  for (bool accessory_board : {false, true}) {
    RplidarDeviceOptions device;
    device.accessory_board = accessory_board;
    Rig rig(device);
    rig.Run([&] {
      if (rig.sink.scan_count() >= 3) {
        EXPECT_TRUE(rig.model.stats().motor_running);
        EXPECT_TRUE(rig.model.stats().scanning);
        return true;
      }
      return false;
    });
    const RplidarDeviceStats& stats = rig.model.stats();
    EXPECT_FALSE(stats.scanning);
    EXPECT_FALSE(stats.motor_running) << "accessory board " << accessory_board;
    EXPECT_EQ(stats.requests.at(kStop), 2) << "one at start, one at the end";
    if (accessory_board) {
      EXPECT_EQ(stats.last_request, kSetMotorPwm);
      EXPECT_EQ(stats.pwm, 0);
      EXPECT_EQ(stats.requests.at(kSetMotorPwm), 2);  // 660 to start, 0 to stop
    } else {
      ASSERT_TRUE(stats.host_dtr.has_value());
      EXPECT_TRUE(*stats.host_dtr);
      EXPECT_EQ(stats.last_request, kStop);
      EXPECT_TRUE(stats.last_request_while_scanning);
    }
    EXPECT_EQ(rig.final_status.state, "stopped");
    EXPECT_FALSE(rig.final_status.connected);
  }
}

// The motor on every exit path (issue 15 item 4). A muted device (transmits nothing, still
// carries out requests) keeps turning at PWM 660 after the driver lost its data: the driver must
// stop it however it is interrupted. Before: SIGTERM while the driver waited for a reply, or
// during the backoff before reopening, left the motor turning (pwm 660 at exit), and a stop
// early in a later session sent STOP without PWM 0.
RplidarDeviceOptions WithAccessoryBoard() {
  RplidarDeviceOptions device;
  device.accessory_board = true;
  return device;
}

TEST(RplidarDriverTest, StopWhileWaitingForAReplyStopsTheMotorAtOnce) {
  Rig rig(WithAccessoryBoard());
  int64_t stop_at = -1;
  int64_t stopped_at = -1;
  rig.Run(
      [&] {
        if (stop_at >= 0 && rig.clock.now_us_ >= stop_at) {
          if (stopped_at < 0) stopped_at = rig.clock.now_us_;
          return true;
        }
        return false;
      },
      [&] {
        if (stop_at < 0 && rig.sink.scan_count() >= 3) {
          rig.model.Mute(60000000, rig.clock.now_us_);
          // 1 s without data, 200 ms backoff, reopen, STOP, 20 ms, GET_INFO: 0.3 s into its
          // 1 s reply wait.
          stop_at = rig.clock.now_us_ + 1000000 + 200000 + 20000 + 300000;
        }
      });
  const RplidarDeviceStats& stats = rig.model.stats();
  EXPECT_EQ(rig.open_times_us.size(), 2u);
  EXPECT_FALSE(stats.motor_running);
  EXPECT_EQ(stats.pwm, 0);
  EXPECT_EQ(stats.last_request, kSetMotorPwm);
  // The stop was noticed within one read slice of the reply wait (50 ms), not at its end.
  EXPECT_LE(rig.clock.now_us_ - stop_at, 100000);
  EXPECT_EQ(rig.final_status.state, "stopped");
}

TEST(RplidarDriverTest, StopDuringTheReconnectBackoffStopsTheMotor) {
  Rig rig(WithAccessoryBoard());
  bool muted = false;
  rig.Run(
      [&] {
        const auto status = rig.sink.last_status();
        return muted && status && status->state == "reconnecting";
      },
      [&] {
        if (!muted && rig.sink.scan_count() >= 3) {
          rig.model.Mute(60000000, rig.clock.now_us_);
          muted = true;
        }
      });
  const RplidarDeviceStats& stats = rig.model.stats();
  EXPECT_FALSE(stats.motor_running);
  EXPECT_EQ(stats.pwm, 0);
  EXPECT_EQ(rig.final_status.state, "stopped");
}

TEST(RplidarDriverTest, AStopEarlyInALaterSessionStillSendsPwmZero) {
  Rig rig(WithAccessoryBoard());
  bool muted = false;
  rig.Run([&] { return rig.open_times_us.size() >= 2; },  // the second session just opened
          [&] {
            if (!muted && rig.sink.scan_count() >= 3) {
              rig.model.Mute(1100000, rig.clock.now_us_);
              muted = true;
            }
          });
  const RplidarDeviceStats& stats = rig.model.stats();
  EXPECT_FALSE(stats.motor_running);
  EXPECT_EQ(stats.pwm, 0);
  EXPECT_EQ(stats.requests.at(kSetMotorPwm), 2);  // 660 in the first session, 0 at the end
}

TEST(RplidarDriverTest, AnUnexpectedErrorStillStopsTheScanAndTheMotor) {
  Rig rig;
  EXPECT_THROW(rig.Run([&]() -> bool {
                 if (rig.sink.scan_count() >= 3) {
                   throw std::runtime_error("LCM publish on LASER_SCAN failed");
                 }
                 return false;
               }),
               std::runtime_error);
  const RplidarDeviceStats& stats = rig.model.stats();
  EXPECT_FALSE(stats.scanning);
  EXPECT_FALSE(stats.motor_running);
  EXPECT_EQ(stats.requests.at(kStop), 2);
}

TEST(RplidarDriverTest, FirmwareWithoutExpressScanGetsTheStandardScan) {
  RplidarDeviceOptions device;
  device.info.firmware_minor = 10;  // 1.10: no GET_SAMPLERATE, no EXPRESS_SCAN
  Rig rig(device, ScanMode::kExpress);
  rig.Run([&] { return rig.sink.scan_count() >= 3; });
  EXPECT_EQ(rig.model.stats().requests.count(kExpressScan), 0u);
  EXPECT_EQ(rig.model.stats().requests.count(kGetSampleRate), 0u);
  EXPECT_EQ(rig.model.stats().requests.at(kScan), 1);
  EXPECT_EQ(rig.final_status.scan_mode, "standard");
  ExpectScansMatchTheRoom(rig, 199, 201);
}

// A link that only ever delivers noise (a wrong baud rate looks like this).
class NoiseLink : public ByteStream {
 public:
  explicit NoiseLink(VirtualClock* clock) : clock_(clock) {}
  void Write(const uint8_t*, size_t, int) override {}
  size_t Read(uint8_t* buffer, size_t capacity, int timeout_ms) override {
    clock_->now_us_ += std::min<int64_t>(1000, int64_t{timeout_ms} * 1000);
    const size_t count = std::min<size_t>(capacity, 11);
    for (size_t i = 0; i < count; ++i) {
      state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
      buffer[i] = static_cast<uint8_t>(state_ >> 56);
    }
    return count;
  }
  void FlushInput() override {}
  void SetDtr(bool) override {}
  std::string Describe() const override { return "virtual:noise"; }

 private:
  VirtualClock* clock_;
  uint64_t state_ = 1;
};

TEST(RplidarDriverTest, NoiseInsteadOfRepliesIsReportedAndRetried) {
  VirtualClock clock;
  RecordingSink sink(&clock);
  RplidarDriverOptions options;
  options.port = "virtual";
  int opens = 0;
  RplidarDriver driver(
      options,
      [&]() -> std::unique_ptr<ByteStream> {
        ++opens;
        return std::make_unique<NoiseLink>(&clock);
      },
      &clock, &sink, "LASER_SCAN", "LIDAR_STATUS");
  const int64_t end = clock.now_us_ + 20 * 1000000LL;
  driver.Run([&] { return clock.now_us_ > end; });
  EXPECT_GE(opens, 3);
  EXPECT_EQ(sink.scan_count(), 0u);
  EXPECT_GE(driver.status().reconnects, 3);
  EXPECT_NE(driver.status().last_error.find("no reply to GET_INFO within 1000 ms"),
            std::string::npos)
      << driver.status().last_error;
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
