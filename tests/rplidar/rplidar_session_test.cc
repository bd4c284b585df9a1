// The device session alone: plain reports to a recording output, its log lines to a recording
// log, no message and no bus (the lifecycle with every fault is rplidar_driver_test, through the
// program's adapter).
#include "drivers/rplidar/rplidar_session.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rplidar_test_support.h"

namespace slammtt {
namespace rplidar {
namespace {

using testing_support::kUtimeBase;
using testing_support::VirtualClock;
using testing_support::VirtualLink;

struct RecordingOutput : RplidarSessionOutput {
  void OnLaserScan(const LaserScan& scan) override { scans.push_back(scan); }
  void OnLidarStatus(const LidarStatus& status) override { statuses.push_back(status); }
  std::vector<LaserScan> scans;
  std::vector<LidarStatus> statuses;
};

struct RecordingLog : DriverLog {
  void Write(DriverLogLevel level, const std::string& line) override {
    lines.emplace_back(level, line);
  }
  bool Has(DriverLogLevel level, const std::string& text) const {
    for (const auto& [l, line] : lines) {
      if (l == level && line.find(text) != std::string::npos) return true;
    }
    return false;
  }
  std::vector<std::pair<DriverLogLevel, std::string>> lines;
};

TEST(RplidarSessionTest, ReportsScansAndStatusAsPlainStructsAndSaysWhatItDoes) {
  RplidarDeviceOptions device;
  RplidarDeviceModel model(device);
  VirtualClock clock;
  bool unplugged = false;
  RecordingOutput output;
  RecordingLog log;
  RplidarDriverOptions options;
  options.port = "virtual";
  options.beams.range_max_m = 8.0;
  RplidarSession session(
      options,
      [&]() -> std::unique_ptr<ByteStream> {
        return std::make_unique<VirtualLink>(&model, &clock, &unplugged);
      },
      &clock, &output, &log);
  session.Run([&] { return output.scans.size() >= 5; });

  ASSERT_EQ(output.scans.size(), 5u);
  for (size_t i = 0; i < output.scans.size(); ++i) {
    const LaserScan& scan = output.scans[i];
    EXPECT_EQ(scan.sequence, static_cast<int64_t>(i));
    EXPECT_GT(scan.utime, kUtimeBase);
    EXPECT_DOUBLE_EQ(scan.range_max_m, 8.0);
    EXPECT_DOUBLE_EQ(scan.range_min_m, 0.15);
    EXPECT_GE(scan.beams.angle_rad.size(), 398u);  // 4000 samples/s at 10 Hz
    EXPECT_EQ(scan.beams.range_m.size(), scan.beams.angle_rad.size());
    EXPECT_EQ(scan.beams.valid.size(), scan.beams.angle_rad.size());
    for (size_t b = 0; b < scan.beams.range_m.size(); ++b) {
      if (scan.beams.range_m[b] > 8.0f) {
        EXPECT_FALSE(scan.beams.valid[b]) << "beyond 8 m";
      }
    }
  }

  ASSERT_GE(output.statuses.size(), 3u);
  EXPECT_EQ(output.statuses.front().state, LidarState::kConnecting);
  EXPECT_FALSE(output.statuses.front().health.has_value()) << "no GET_HEALTH answer yet";
  const LidarStatus& last = output.statuses.back();
  EXPECT_EQ(last.state, LidarState::kStopped);
  EXPECT_FALSE(last.connected);
  EXPECT_EQ(last.endpoint, "virtual:rplidar");
  EXPECT_EQ(last.model, 0x28);
  ASSERT_TRUE(last.health.has_value());
  EXPECT_EQ(last.health->status, HealthStatus::kGood);
  EXPECT_EQ(last.scan_mode, ScanMode::kExpress);
  EXPECT_EQ(last.scans_published, 5);
  EXPECT_EQ(last.utime, clock.NowUtime());
  bool scanning_reported = false;
  for (const LidarStatus& status : output.statuses) {
    scanning_reported = scanning_reported || status.state == LidarState::kScanning;
  }
  EXPECT_TRUE(scanning_reported);
  EXPECT_EQ(session.status().state, LidarState::kStopped);

  EXPECT_TRUE(log.Has(DriverLogLevel::kInfo,
                      "connected to virtual:rplidar: model 0x0028, firmware 1.29, hardware 7, "
                      "serial 5EA13C001D429B278064C31107F2382A, health good"));
  EXPECT_TRUE(log.Has(DriverLogLevel::kInfo, "scanning (express)"));
  EXPECT_TRUE(log.Has(DriverLogLevel::kInfo, "scan stopped, motor off"));
}

TEST(RplidarSessionTest, ALostLinkIsAWarningAndAReconnectingStatus) {
  VirtualClock clock;
  RecordingOutput output;
  RecordingLog log;
  RplidarDriverOptions options;
  options.port = "virtual";
  int opens = 0;
  RplidarSession session(
      options,
      [&]() -> std::unique_ptr<ByteStream> {
        ++opens;
        throw LinkError("virtual:rplidar: no such device");
      },
      &clock, &output, &log);
  session.Run([&] { return opens >= 3; });
  EXPECT_TRUE(log.Has(DriverLogLevel::kWarning,
                      "virtual:rplidar: no such device; reopening in 200 ms"));
  EXPECT_TRUE(log.Has(DriverLogLevel::kWarning, "reopening in 400 ms"));
  bool reconnecting = false;
  for (const LidarStatus& status : output.statuses) {
    if (status.state == LidarState::kReconnecting) {
      reconnecting = true;
      EXPECT_FALSE(status.connected);
      EXPECT_EQ(status.last_error, "virtual:rplidar: no such device");
    }
  }
  EXPECT_TRUE(reconnecting);
  EXPECT_EQ(session.status().reconnects, 3);  // every failed open
  EXPECT_TRUE(output.scans.empty());
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
