// The world's events as LCM messages (lcmtypes/), in the order and with the timestamps of the
// channel contract (docs/world.md):
//   - every message's utime = utime_offset + simulated time; a log event's timestamp = utime;
//   - at equal utime: ODOMETRY, then LASER_GEOMETRY, then GROUND_TRUTH, then LASER_SCAN, then
//     FEATURES;
//   - LASER_GEOMETRY with the first sensor frame and then with every round(rate_hz)-th (about
//     once a second), so that a log read from any of those frames on has it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "tools/world/world_simulator.h"

namespace slammtt {

slammtt_msgs::odometry_t ToOdometryMessage(const OdometryReading& reading, int64_t utime_offset);
// object_class STATIC/MOVING from the scenario; beams_on_object and visible as in ObjectTruth.
slammtt_msgs::ground_truth_t ToGroundTruthMessage(const TruthSnapshot& truth, int64_t utime_offset);
// Every beam, invalid ones with valid = false and range 0; intensity 1 on a valid return, else 0;
// scan_duration_us 0 (instantaneous scan).
slammtt_msgs::laser_scan_t ToLaserScanMessage(const SensorFrame& frame, const LaserSpec& laser,
                                              int64_t utime_offset);
// The laser's mount, field of view (fov_deg centred on the laser's heading) and ranges, as the
// scenario gives them; source names the scenario.
slammtt_msgs::laser_geometry_t ToLaserGeometryMessage(const Scenario& scenario, int64_t utime);
// Whether the sensor frame of this sequence number carries a LASER_GEOMETRY.
bool FrameCarriesGeometry(const LaserSpec& laser, int64_t sequence);
// Range/bearing of object centres; width = diameter, num_points 0, variances = noise variances.
slammtt_msgs::features_t ToFeaturesMessage(const SensorFrame& frame, int64_t utime_offset);

// Channel names the world publishes on.
struct WorldChannels {
  std::string odometry = "ODOMETRY";
  std::string ground_truth = "GROUND_TRUTH";
  std::string laser_scan = "LASER_SCAN";
  std::string laser_geometry = "LASER_GEOMETRY";
  std::string features = "FEATURES";
};

// One encoded message.
struct EncodedMessage {
  int64_t utime = 0;
  std::string channel;
  std::vector<uint8_t> data;
};

// The messages of one event, in contract order: one ODOMETRY for an odometry event;
// LASER_GEOMETRY (FrameCarriesGeometry), GROUND_TRUTH, then LASER_SCAN and/or FEATURES (as the
// frame has them) for a sensor event.
std::vector<EncodedMessage> EncodeWorldEvent(const WorldEvent& event, const Scenario& scenario,
                                             const WorldChannels& channels, int64_t utime_offset);

}  // namespace slammtt
