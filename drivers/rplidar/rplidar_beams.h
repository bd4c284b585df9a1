// From RPLIDAR samples to beams in our sensor frame.
//
// The RPLIDAR reports angles in degrees growing CLOCKWISE seen from above, from the device's
// own 0 (protocol document, "Scan response": "the heading angle ... in clockwise direction";
// ROS drivers negate it for the same reason). Our sensor frame (docs/DEVELOPING.md) has x
// forward, y left and angles growing counter-clockwise. With the device upright and its 0
// direction along the sensor frame's x axis:
//   angle_rad = wrap(radians(angle_offset_deg - device_angle_deg))
// `angle_offset_deg` is where the device's 0 points in the sensor frame, CCW from x (e.g. 180
// when the device's 0 faces backwards, as in the rplidar_ros convention); `upside_down` flips
// the direction of rotation (device mounted inverted): angle_offset_deg + device_angle_deg.
// wrap() maps to (-pi, pi].
//
// Ranges: distance 0 is no return (valid = false, range 0). A distance outside
// [range_min_m, range_max_m] is kept with its measured range and valid = false, so nothing is
// silently lost (laser_scan_t's contract). Intensity is the sample quality, 0..63.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/rplidar/rplidar_scan_decoder.h"

namespace slammtt {
namespace rplidar {

struct BeamConversionOptions {
  double angle_offset_deg = 0.0;
  bool upside_down = false;
  double range_min_m = 0.15;  // RPLIDAR A2 datasheet: measuring range from 0.15 m
  double range_max_m = 12.0;  // A2M8 datasheet: up to 12 m (A2M12: 16 m)
};

struct Beams {
  std::vector<float> angle_rad;
  std::vector<float> range_m;
  std::vector<float> intensity;
  std::vector<bool> valid;
};

// Sensor-frame direction of a device angle, in (-pi, pi].
double DeviceAngleToSensorRad(double device_angle_deg, const BeamConversionOptions& options);

// One beam per sample, in the order the device produced them.
Beams ConvertRevolution(const std::vector<ScanSample>& samples,
                        const BeamConversionOptions& options);

}  // namespace rplidar
}  // namespace slammtt
