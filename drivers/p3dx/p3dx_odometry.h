// Wheel odometry of the P3-DX from its standard SIPs.
//
// The firmware integrates the pose itself and sends it as XPOS, YPOS (15-bit counters that wrap)
// and THPOS (4096 units per revolution). The host only converts and unwraps:
//  - position: the difference of consecutive XPOS (YPOS) readings modulo 2^15, taken into
//    [-16384, 16383], times DistConvFactor (32760 -> 5 is +13 units). ARIA (ArRobot::
//    processMotorPacket) unwraps with a 0x1000 threshold; modular arithmetic is exact for any
//    step under 16384 units (7.9 m per SIP cycle on a p3dx);
//  - heading: THPOS times AngleConvFactor, modulo one revolution, so a firmware that sends
//    0..4095 and one that sends signed values give the same heading;
//  - wheel speeds: L VEL, R VEL times VelConvFactor; linear speed their mean;
//  - yaw rate: ROTVEL (0.1 deg/s) when the SIP has it, else (R - L) / effective track, where the
//    effective track is 2 / DiffConvFactor (357 mm for DiffConvFactor 0.0056, wider than the
//    316 mm between the wheels because it includes tyre scrub; ARIA, p2os and MobileSim all use
//    DiffConvFactor).
// Conversion factors: ARIA params/p3dx.p and p3dx-sh.p (see ../shared/design/protocols/p3dx.md).
//
// The odometry frame starts at (0, 0, 0) at the first SIP and stays continuous across
// reconnections: after Reanchor() the next SIP becomes a new anchor whose pose is the last pose
// reported, and later motion is rotated from the firmware's (possibly reset) frame into ours.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "drivers/p3dx/p3dx_sip.h"

namespace slammtt {

// Conversion factors of one Pioneer model (ARIA parameter file names in brackets).
struct P3dxConversion {
  double dist_conv_mm = 0.485;                    // mm per XPOS/YPOS unit [DistConvFactor]
  double angle_conv_rad = 0.0015339807878856412;  // 2*pi/4096 rad per THPOS unit (ARIA's file
                                                  // rounds it to 0.00153) [AngleConvFactor]
  double vel_conv = 1.0;                          // mm/s per velocity unit [VelConvFactor]
  double diff_conv = 0.0056;                      // [DiffConvFactor]
  double vel2_divisor = 20.0;                     // mm/s per VEL2 unit [Vel2Divisor]

  double effective_track_m() const { return 2.0 / diff_conv / 1000.0; }
};

// The factors for a subclass named in the SYNC2 reply: "p3dx" has DistConvFactor 0.485, the
// "p3dx-sh..." family 1.0. nullopt for a subclass we have no parameters for.
std::optional<P3dxConversion> P3dxConversionForSubclass(const std::string& subclass);

// Signed difference to - from of two 15-bit position counters, in [-16384, 16383].
int P3dxPositionDelta(uint16_t from, uint16_t to);
// THPOS as an angle in (-pi, pi].
double P3dxHeadingRad(int16_t th_pos, const P3dxConversion& conversion);
struct P3dxOdometry {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;  // (-pi, pi]
  double linear_velocity_mps = 0.0;
  double angular_velocity_radps = 0.0;
  double left_wheel_velocity_mps = 0.0;
  double right_wheel_velocity_mps = 0.0;
};

class P3dxOdometryIntegrator {
 public:
  explicit P3dxOdometryIntegrator(const P3dxConversion& conversion = P3dxConversion{});

  // Factors for the SIPs from now on (after a connect revealed the subclass).
  void SetConversion(const P3dxConversion& conversion) { conversion_ = conversion; }
  const P3dxConversion& conversion() const { return conversion_; }
  // The next SIP starts a new anchor (a new session: the firmware may have reset its counters).
  void Reanchor() { anchored_ = false; }

  // Integrates one parsed SIP and returns the odometry it gives.
  P3dxOdometry Update(const P3dxStandardSip& sip);

 private:
  P3dxConversion conversion_;
  bool anchored_ = false;
  uint16_t last_x_pos_ = 0;
  uint16_t last_y_pos_ = 0;
  // Our frame = the firmware's frame rotated by frame_rotation_rad_ (set at each anchor).
  double frame_rotation_rad_ = 0.0;
  P3dxOdometry last_;
};

}  // namespace slammtt
