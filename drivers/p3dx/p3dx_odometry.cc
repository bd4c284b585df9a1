#include "drivers/p3dx/p3dx_odometry.h"

#include <cmath>

#include "common/angle.h"

namespace slammtt {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::optional<P3dxConversion> P3dxConversionForSubclass(const std::string& subclass) {
  P3dxConversion conversion;
  if (subclass == "p3dx") {
    conversion.dist_conv_mm = 0.485;
    return conversion;
  }
  if (subclass.rfind("p3dx-sh", 0) == 0) {
    conversion.dist_conv_mm = 1.0;
    return conversion;
  }
  return std::nullopt;
}

int P3dxPositionDelta(uint16_t from, uint16_t to) {
  int delta = (static_cast<int>(to & 0x7FFF) - static_cast<int>(from & 0x7FFF)) & 0x7FFF;
  if (delta >= 0x4000) delta -= 0x8000;
  return delta;
}

double P3dxHeadingRad(int16_t th_pos, const P3dxConversion& conversion) {
  // Modulo 4096 first, so that the angle does not depend on how the firmware signs THPOS.
  const int units = ((static_cast<int>(th_pos) % 4096) + 4096) % 4096;
  return WrapAngle(units * conversion.angle_conv_rad);
}

P3dxOdometryIntegrator::P3dxOdometryIntegrator(const P3dxConversion& conversion)
    : conversion_(conversion) {}

P3dxOdometry P3dxOdometryIntegrator::Update(const P3dxStandardSip& sip) {
  const double firmware_heading = P3dxHeadingRad(sip.th_pos, conversion_);
  P3dxOdometry odometry = last_;
  if (!anchored_) {
    // Keep the pose we reported last; rotate the firmware's frame onto ours.
    frame_rotation_rad_ = last_.heading_rad - firmware_heading;
    anchored_ = true;
  } else {
    const double dx_m = P3dxPositionDelta(last_x_pos_, sip.x_pos) * conversion_.dist_conv_mm / 1000.0;
    const double dy_m = P3dxPositionDelta(last_y_pos_, sip.y_pos) * conversion_.dist_conv_mm / 1000.0;
    const double c = std::cos(frame_rotation_rad_);
    const double s = std::sin(frame_rotation_rad_);
    odometry.x_m += c * dx_m - s * dy_m;
    odometry.y_m += s * dx_m + c * dy_m;
  }
  last_x_pos_ = sip.x_pos;
  last_y_pos_ = sip.y_pos;
  odometry.heading_rad = WrapAngle(firmware_heading + frame_rotation_rad_);

  odometry.left_wheel_velocity_mps = sip.left_vel * conversion_.vel_conv / 1000.0;
  odometry.right_wheel_velocity_mps = sip.right_vel * conversion_.vel_conv / 1000.0;
  odometry.linear_velocity_mps =
      0.5 * (odometry.left_wheel_velocity_mps + odometry.right_wheel_velocity_mps);
  if (sip.rot_vel_decideg_per_s) {
    odometry.angular_velocity_radps = *sip.rot_vel_decideg_per_s * 0.1 * kPi / 180.0;
  } else {
    odometry.angular_velocity_radps =
        (odometry.right_wheel_velocity_mps - odometry.left_wheel_velocity_mps) /
        conversion_.effective_track_m();
  }
  last_ = odometry;
  return odometry;
}

}  // namespace slammtt
