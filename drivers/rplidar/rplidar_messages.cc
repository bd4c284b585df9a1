#include "drivers/rplidar/rplidar_messages.h"

#include <cmath>

namespace slammtt {
namespace rplidar {

slammtt_msgs::laser_scan_t LaserScanMessage(const LaserScan& scan) {
  slammtt_msgs::laser_scan_t message;
  message.utime = scan.utime;
  message.sequence = scan.sequence;
  message.scan_duration_us = scan.scan_duration_us;
  message.range_min_m = static_cast<float>(scan.range_min_m);
  message.range_max_m = static_cast<float>(scan.range_max_m);
  message.num_beams = static_cast<int32_t>(scan.beams.angle_rad.size());
  message.angle_rad = scan.beams.angle_rad;
  message.range_m = scan.beams.range_m;
  message.intensity = scan.beams.intensity;
  message.valid.assign(scan.beams.valid.begin(), scan.beams.valid.end());
  return message;
}

slammtt_msgs::lidar_status_t LidarStatusMessage(const LidarStatus& status) {
  slammtt_msgs::lidar_status_t message;
  message.utime = status.utime;
  message.connected = status.connected;
  message.state = LidarStateName(status.state);
  message.endpoint = status.endpoint;
  message.model = status.model;
  message.firmware_major = status.firmware_major;
  message.firmware_minor = status.firmware_minor;
  message.hardware = status.hardware;
  message.serial_number = status.serial_number;
  message.health = status.health ? static_cast<int8_t>(status.health->status)
                                 : slammtt_msgs::lidar_status_t::HEALTH_UNKNOWN;
  message.health_error_code = status.health ? status.health->error_code : 0;
  message.scan_mode = ScanModeName(status.scan_mode);
  message.scan_rate_hz = status.scan_rate_hz;
  message.scans_published = status.scans_published;
  message.nodes_decoded = status.nodes_decoded;
  message.resyncs = status.resyncs;
  message.checksum_errors = status.checksum_errors;
  message.reconnects = status.reconnects;
  message.last_error = status.last_error;
  return message;
}

slammtt_msgs::laser_geometry_t LaserGeometryMessage(const RplidarDriverOptions& options,
                                                    int64_t utime) {
  slammtt_msgs::laser_geometry_t message{};
  message.utime = utime;
  message.mount_forward_m = options.mount_forward_m;
  message.mount_left_m = options.mount_left_m;
  message.mount_yaw_rad = options.mount_yaw_deg * M_PI / 180.0;
  message.view_start_rad = -M_PI;  // a full revolution (rplidar_beams.h: angles in (-pi, pi])
  message.view_end_rad = M_PI;
  message.range_min_m = options.beams.range_min_m;
  message.range_max_m = options.beams.range_max_m;
  message.source = "slammtt-rplidar, rplidar: section";
  return message;
}

}  // namespace rplidar
}  // namespace slammtt
