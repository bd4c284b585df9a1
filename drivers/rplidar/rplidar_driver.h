// The RPLIDAR driver as the program runs it: the device session (rplidar_session.h, pure)
// publishing its reports as LASER_SCAN and LIDAR_STATUS on a MessageSink (rplidar_messages.h),
// each LIDAR_STATUS followed by a LASER_GEOMETRY (the options' mount) when that channel is
// given, and its log lines to the process log. Everything the driver does is the session's;
// this is the bus around it.
#pragma once

#include <functional>
#include <string>

#include "drivers/common/runtime_driver_log.h"
#include "drivers/rplidar/rplidar_session.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/lidar_status_t.hpp"

namespace slammtt {
namespace rplidar {

// Publishes a session's reports on a bus; after each LIDAR_STATUS, the scans' geometry with
// the status's time (the estimator takes the mount from there: docs/estimator.md).
class RplidarMessagePublisher : public RplidarSessionOutput {
 public:
  RplidarMessagePublisher(const RplidarDriverOptions& options, MessageSink* sink,
                          std::string laser_scan_channel, std::string lidar_status_channel,
                          std::string laser_geometry_channel);
  void OnLaserScan(const LaserScan& scan) override;
  void OnLidarStatus(const LidarStatus& status) override;

 private:
  MessageSink* sink_;
  std::string laser_scan_channel_;
  std::string lidar_status_channel_;
  std::string laser_geometry_channel_;  // "": no LASER_GEOMETRY
  slammtt_msgs::laser_geometry_t geometry_;  // the options', stamped per status
};

class RplidarDriver {
 public:
  using StreamFactory = RplidarSession::StreamFactory;

  RplidarDriver(const RplidarDriverOptions& options, StreamFactory open_stream,
                DriverClock* clock, MessageSink* sink, std::string laser_scan_channel,
                std::string lidar_status_channel, std::string laser_geometry_channel = "");

  // RplidarSession::Run: until should_stop(), publishing as it goes.
  void Run(const std::function<bool()>& should_stop) { session_.Run(should_stop); }

  // The LIDAR_STATUS last published.
  slammtt_msgs::lidar_status_t status() const;

 private:
  RplidarMessagePublisher publisher_;
  RuntimeDriverLog log_;
  RplidarSession session_;
};

}  // namespace rplidar
}  // namespace slammtt
