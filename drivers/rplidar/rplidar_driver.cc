#include "drivers/rplidar/rplidar_driver.h"

#include <utility>

#include "drivers/rplidar/rplidar_messages.h"

namespace slammtt {
namespace rplidar {

RplidarMessagePublisher::RplidarMessagePublisher(const RplidarDriverOptions& options,
                                                 MessageSink* sink,
                                                 std::string laser_scan_channel,
                                                 std::string lidar_status_channel,
                                                 std::string laser_geometry_channel)
    : sink_(sink),
      laser_scan_channel_(std::move(laser_scan_channel)),
      lidar_status_channel_(std::move(lidar_status_channel)),
      laser_geometry_channel_(std::move(laser_geometry_channel)),
      geometry_(LaserGeometryMessage(options, 0)) {}

void RplidarMessagePublisher::OnLaserScan(const LaserScan& scan) {
  sink_->PublishMessage(laser_scan_channel_, LaserScanMessage(scan));
}

void RplidarMessagePublisher::OnLidarStatus(const LidarStatus& status) {
  sink_->PublishMessage(lidar_status_channel_, LidarStatusMessage(status));
  if (!laser_geometry_channel_.empty()) {
    geometry_.utime = status.utime;
    sink_->PublishMessage(laser_geometry_channel_, geometry_);
  }
}

RplidarDriver::RplidarDriver(const RplidarDriverOptions& options, StreamFactory open_stream,
                             DriverClock* clock, MessageSink* sink,
                             std::string laser_scan_channel, std::string lidar_status_channel,
                             std::string laser_geometry_channel)
    : publisher_(options, sink, std::move(laser_scan_channel), std::move(lidar_status_channel),
                 std::move(laser_geometry_channel)),
      session_(options, std::move(open_stream), clock, &publisher_, &log_) {}

slammtt_msgs::lidar_status_t RplidarDriver::status() const {
  return LidarStatusMessage(session_.status());
}

}  // namespace rplidar
}  // namespace slammtt
