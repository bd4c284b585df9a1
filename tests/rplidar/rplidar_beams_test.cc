#include "drivers/rplidar/rplidar_beams.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slammtt {
namespace rplidar {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(RplidarBeamsTest, ClockwiseDeviceAnglesBecomeCounterClockwise) {
  const BeamConversionOptions options;
  EXPECT_NEAR(DeviceAngleToSensorRad(0.0, options), 0.0, 1e-12);
  EXPECT_NEAR(DeviceAngleToSensorRad(90.0, options), -kPi / 2, 1e-12);  // to the right
  EXPECT_NEAR(DeviceAngleToSensorRad(270.0, options), kPi / 2, 1e-12);  // to the left
  EXPECT_NEAR(DeviceAngleToSensorRad(180.0, options), kPi, 1e-12);      // (-pi, pi]
  EXPECT_NEAR(DeviceAngleToSensorRad(359.0, options), kPi / 180.0, 1e-12);
}

TEST(RplidarBeamsTest, OffsetAndUpsideDownMount) {
  BeamConversionOptions options;
  options.angle_offset_deg = 180.0;
  EXPECT_NEAR(DeviceAngleToSensorRad(0.0, options), kPi, 1e-12);
  EXPECT_NEAR(DeviceAngleToSensorRad(90.0, options), kPi / 2, 1e-12);
  options.angle_offset_deg = 0.0;
  options.upside_down = true;
  EXPECT_NEAR(DeviceAngleToSensorRad(90.0, options), kPi / 2, 1e-12);
}

TEST(RplidarBeamsTest, ValidityFollowsDistanceAndRangeLimits) {
  std::vector<ScanSample> samples(4);
  samples[0].distance_q2 = 4000;  // 1 m
  samples[0].quality = 47;
  samples[1].distance_q2 = 0;     // no return
  samples[2].distance_q2 = 400;   // 0.1 m: below 0.15 m
  samples[3].distance_q2 = 52000; // 13 m: beyond 12 m
  const Beams beams = ConvertRevolution(samples, BeamConversionOptions());
  ASSERT_EQ(beams.valid.size(), 4u);
  EXPECT_TRUE(beams.valid[0]);
  EXPECT_FLOAT_EQ(beams.range_m[0], 1.0f);
  EXPECT_FLOAT_EQ(beams.intensity[0], 47.0f);
  EXPECT_FALSE(beams.valid[1]);
  EXPECT_FLOAT_EQ(beams.range_m[1], 0.0f);
  EXPECT_FALSE(beams.valid[2]);
  EXPECT_FLOAT_EQ(beams.range_m[2], 0.1f);
  EXPECT_FALSE(beams.valid[3]);
  EXPECT_FLOAT_EQ(beams.range_m[3], 13.0f);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
