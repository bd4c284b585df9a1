#include "drivers/rplidar/rplidar_beams.h"

#include <cmath>

#include "common/angle.h"

namespace slammtt {
namespace rplidar {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double DeviceAngleToSensorRad(double device_angle_deg, const BeamConversionOptions& options) {
  const double degrees = options.upside_down ? options.angle_offset_deg + device_angle_deg
                                             : options.angle_offset_deg - device_angle_deg;
  return WrapAngle(degrees * kPi / 180.0);
}

Beams ConvertRevolution(const std::vector<ScanSample>& samples,
                        const BeamConversionOptions& options) {
  Beams beams;
  beams.angle_rad.reserve(samples.size());
  beams.range_m.reserve(samples.size());
  beams.intensity.reserve(samples.size());
  beams.valid.reserve(samples.size());
  for (const ScanSample& sample : samples) {
    const double range_m = sample.DistanceMm() / 1000.0;
    beams.angle_rad.push_back(static_cast<float>(DeviceAngleToSensorRad(sample.AngleDeg(), options)));
    beams.range_m.push_back(static_cast<float>(range_m));
    beams.intensity.push_back(static_cast<float>(sample.quality));
    beams.valid.push_back(sample.distance_q2 != 0 && range_m >= options.range_min_m &&
                          range_m <= options.range_max_m);
  }
  return beams;
}

}  // namespace rplidar
}  // namespace slammtt
