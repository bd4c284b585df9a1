// The RPLIDAR session's reports as LCM messages: LaserScan -> laser_scan_t (LASER_SCAN),
// LidarStatus -> lidar_status_t (LIDAR_STATUS). Field for field; the only conversions are the
// message's float ranges, its beam count and valid bytes, its health code (-1 before the first
// GET_HEALTH) and its state and scan mode names. And the geometry of the scans, from the
// options (LASER_GEOMETRY, published with every LIDAR_STATUS).
#pragma once

#include <cstdint>

#include "drivers/rplidar/rplidar_driver_options.h"
#include "drivers/rplidar/rplidar_session_output.h"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/lidar_status_t.hpp"

namespace slammtt {
namespace rplidar {

slammtt_msgs::laser_scan_t LaserScanMessage(const LaserScan& scan);
slammtt_msgs::lidar_status_t LidarStatusMessage(const LidarStatus& status);
// The geometry of the scans the driver publishes: the options' mount (yaw in radians), a full
// revolution, the options' valid range; stamped `utime`.
slammtt_msgs::laser_geometry_t LaserGeometryMessage(const RplidarDriverOptions& options,
                                                    int64_t utime);

}  // namespace rplidar
}  // namespace slammtt
