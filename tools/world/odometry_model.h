// Wheel odometry of the synthetic differential-drive base, paper eq. 1:
//   x(k+1)   = x(k) + Omega_r dt cos(phi(k) + Omega_d dt)
//   y(k+1)   = y(k) + Omega_r dt sin(phi(k) + Omega_d dt)
//   phi(k+1) = phi(k) + Omega_d dt
// with Omega_r = (w_R + w_L) r / 2 and Omega_d = (w_R - w_L) r / D, r the wheel radius, D the
// distance between the wheels, w_R, w_L the wheel angular velocities (here: encoder increments
// divided by dt).
#pragma once

#include <cstdint>
#include <random>

#include "tools/world/planar_pose.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Rotation of each wheel over one interval [rad].
struct WheelIncrements {
  double left_rad = 0.0;
  double right_rad = 0.0;
};

// The wheel rotations that move the axle centre `distance_m` forward while the heading turns by
// `rotation_rad` (exact for any path: each wheel travels distance -+ rotation * D / 2).
WheelIncrements WheelIncrementsForMotion(double distance_m, double rotation_rad,
                                         double wheel_radius_m, double axle_length_m);

// One step of paper eq. 1 with the increments of one interval (Omega dt = increments * r ...).
Pose2D IntegrateWheelIncrements(const Pose2D& pose, const WheelIncrements& increments,
                                double wheel_radius_m, double axle_length_m);

// What the encoders read for the true increments (OdometrySpec: slip and encoder noise). Draws
// from `rng` only for non-zero noise terms.
WheelIncrements MeasureWheelIncrements(const WheelIncrements& truth, const OdometrySpec& spec,
                                       std::mt19937_64& rng);

// One odometry reading as the base reports it.
struct OdometryReading {
  int64_t time_us = 0;   // since the scenario start
  int64_t sequence = 0;  // 0, 1, 2, ...
  Pose2D pose;           // integrated in the odometry frame, starting at (0, 0, 0)
  // Measured over the interval that ends at this reading (0 for the first reading).
  double linear_mps = 0.0;
  double angular_radps = 0.0;
  double left_wheel_mps = 0.0;   // wheel surface speeds
  double right_wheel_mps = 0.0;
};

// The base's odometry: integrates measured increments with eq. 1.
class OdometryIntegrator {
 public:
  explicit OdometryIntegrator(const OdometrySpec& spec);
  // The first reading: pose (0, 0, 0), zero velocities.
  OdometryReading Start(int64_t time_us);
  // The reading at time_us after the axle centre truly travelled distance_m (signed) and turned
  // by rotation_rad since the previous reading.
  OdometryReading Update(int64_t time_us, double distance_m, double rotation_rad,
                         std::mt19937_64& rng);

 private:
  OdometrySpec spec_;
  Pose2D pose_;
  int64_t last_time_us_ = 0;
  int64_t sequence_ = 0;
};

}  // namespace slammtt
