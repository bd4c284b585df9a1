// The RPLIDAR session's plain reports become LASER_SCAN and LIDAR_STATUS field for field, and
// the options' mount and range become LASER_GEOMETRY.
#include "drivers/rplidar/rplidar_messages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace slammtt {
namespace rplidar {
namespace {

TEST(RplidarMessagesTest, LaserScanMapsEveryField) {
  LaserScan scan;
  scan.utime = 1700000000123456;
  scan.sequence = 42;
  scan.scan_duration_us = 99876;
  scan.range_min_m = 0.15;
  scan.range_max_m = 12.0;
  scan.beams.angle_rad = {-3.0f, 0.5f, 3.1f};
  scan.beams.range_m = {1.25f, 0.0f, 20.5f};
  scan.beams.intensity = {47.0f, 0.0f, 12.0f};
  scan.beams.valid = {true, false, false};
  const slammtt_msgs::laser_scan_t message = LaserScanMessage(scan);
  EXPECT_EQ(message.utime, 1700000000123456);
  EXPECT_EQ(message.sequence, 42);
  EXPECT_EQ(message.scan_duration_us, 99876);
  EXPECT_EQ(message.range_min_m, 0.15f);
  EXPECT_EQ(message.range_max_m, 12.0f);
  EXPECT_EQ(message.num_beams, 3);
  EXPECT_EQ(message.angle_rad, scan.beams.angle_rad);
  EXPECT_EQ(message.range_m, scan.beams.range_m);
  EXPECT_EQ(message.intensity, scan.beams.intensity);
  EXPECT_EQ(message.valid, (std::vector<int8_t>{1, 0, 0}));
}

TEST(RplidarMessagesTest, AnEmptyScanHasNoBeams) {
  const slammtt_msgs::laser_scan_t message = LaserScanMessage(LaserScan{});
  EXPECT_EQ(message.num_beams, 0);
  EXPECT_TRUE(message.angle_rad.empty());
  EXPECT_TRUE(message.valid.empty());
}

TEST(RplidarMessagesTest, LidarStatusMapsEveryField) {
  LidarStatus status;
  status.utime = 1700000000654321;
  status.connected = true;
  status.state = LidarState::kScanning;
  status.endpoint = "tcp://127.0.0.1:4001";
  status.model = 0x28;
  status.firmware_major = 1;
  status.firmware_minor = 29;
  status.hardware = 7;
  status.serial_number = "5EA13C001D429B278064C31107F2382A";
  status.health = DeviceHealth{HealthStatus::kWarning, 0x1234};
  status.scan_mode = ScanMode::kStandard;
  status.scan_rate_hz = 9.75;
  status.scans_published = 11;
  status.nodes_decoded = 12;
  status.resyncs = 13;
  status.checksum_errors = 14;
  status.reconnects = 15;
  status.last_error = "virtual: unplugged";
  const slammtt_msgs::lidar_status_t message = LidarStatusMessage(status);
  EXPECT_EQ(message.utime, 1700000000654321);
  EXPECT_TRUE(message.connected);
  EXPECT_EQ(message.state, "scanning");
  EXPECT_EQ(message.endpoint, "tcp://127.0.0.1:4001");
  EXPECT_EQ(message.model, 0x28);
  EXPECT_EQ(message.firmware_major, 1);
  EXPECT_EQ(message.firmware_minor, 29);
  EXPECT_EQ(message.hardware, 7);
  EXPECT_EQ(message.serial_number, "5EA13C001D429B278064C31107F2382A");
  EXPECT_EQ(int{message.health}, int{slammtt_msgs::lidar_status_t::HEALTH_WARNING});
  EXPECT_EQ(message.health_error_code, 0x1234);
  EXPECT_EQ(message.scan_mode, "standard");
  EXPECT_EQ(message.scan_rate_hz, 9.75);
  EXPECT_EQ(message.scans_published, 11);
  EXPECT_EQ(message.nodes_decoded, 12);
  EXPECT_EQ(message.resyncs, 13);
  EXPECT_EQ(message.checksum_errors, 14);
  EXPECT_EQ(message.reconnects, 15);
  EXPECT_EQ(message.last_error, "virtual: unplugged");
}

TEST(RplidarMessagesTest, HealthIsUnknownBeforeTheFirstAnswer) {
  LidarStatus status;
  status.endpoint = "/dev/ttyUSB0";
  const slammtt_msgs::lidar_status_t message = LidarStatusMessage(status);
  EXPECT_EQ(int{message.health}, int{slammtt_msgs::lidar_status_t::HEALTH_UNKNOWN});
  EXPECT_EQ(message.health_error_code, 0);
  EXPECT_EQ(message.state, "connecting");
  EXPECT_FALSE(message.connected);
  EXPECT_EQ(message.scan_mode, "express");
  status.health = DeviceHealth{HealthStatus::kGood, 0};
  EXPECT_EQ(int{LidarStatusMessage(status).health},
            int{slammtt_msgs::lidar_status_t::HEALTH_GOOD});
  status.health = DeviceHealth{HealthStatus::kError, 0x0042};
  EXPECT_EQ(int{LidarStatusMessage(status).health},
            int{slammtt_msgs::lidar_status_t::HEALTH_ERROR});
  EXPECT_EQ(LidarStatusMessage(status).health_error_code, 0x0042);
}

TEST(RplidarMessagesTest, StateNamesAreTheMessagesSpelling) {
  const std::vector<std::pair<LidarState, std::string>> names = {
      {LidarState::kConnecting, "connecting"},    {LidarState::kScanning, "scanning"},
      {LidarState::kReconnecting, "reconnecting"}, {LidarState::kHealthError, "health_error"},
      {LidarState::kStopped, "stopped"}};
  for (const auto& [state, name] : names) {
    LidarStatus status;
    status.state = state;
    EXPECT_EQ(LidarStatusMessage(status).state, name);
  }
}

TEST(RplidarMessagesTest, LaserGeometryIsTheOptionsMountAndRange) {
  RplidarDriverOptions options;
  options.mount_forward_m = 0.12;
  options.mount_left_m = -0.03;
  options.mount_yaw_deg = -90.0;
  options.beams.range_min_m = 0.2;
  options.beams.range_max_m = 16.0;
  const slammtt_msgs::laser_geometry_t message = LaserGeometryMessage(options, 1700000000000042);
  EXPECT_EQ(message.utime, 1700000000000042);
  EXPECT_EQ(message.mount_forward_m, 0.12);
  EXPECT_EQ(message.mount_left_m, -0.03);
  EXPECT_EQ(message.mount_yaw_rad, -M_PI / 2.0);
  EXPECT_EQ(message.view_start_rad, -M_PI);
  EXPECT_EQ(message.view_end_rad, M_PI);
  EXPECT_EQ(message.range_min_m, 0.2);
  EXPECT_EQ(message.range_max_m, 16.0);
  EXPECT_EQ(message.source, "slammtt-rplidar, rplidar: section");
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
