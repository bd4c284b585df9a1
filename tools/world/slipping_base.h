// The true motion of a differential-drive base whose wheel encoders report a given motion: the
// ground under a wheel moves by what its encoder counted divided by (1 + bias + slip), the
// inverse of OdometrySpec's encoder model (measured = true * (1 + bias + slip)), so that the
// odometry the base reports drifts from the truth as the scenario's odometry says. The slip of
// each wheel is drawn N(0, slip_std^2) anew every odometry period (1 / rate_hz of time), as
// OdometrySpec draws it per reading. The encoders' additive noise is left out: a base that
// reports its own counts (the P3-DX emulator, drivers/p3dx/p3dx_robot_model.h) counts exactly.
//
// Used by the simulated robot (drivers/sim_robot): the emulated base integrates the velocities
// it is commanded into its encoder pose; this turns the encoder pose's steps into the world's
// true pose. Pure: no clock, randomness from a seed.
#pragma once

#include <cstdint>
#include <random>

#include "tools/world/planar_pose.h"
#include "tools/world/scenario.h"

namespace slammtt {

// The distance (signed, along the arc) and the rotation of the step from `from` to `to` when
// the base moved on one circular arc (or a straight line) between them: what its wheels
// travelled. A step with a sideways part (impossible for a differential drive) is taken along
// its chord.
struct ArcStep {
  double distance_m = 0.0;
  double rotation_rad = 0.0;
};
ArcStep ArcStepBetween(const Pose2D& from, const Pose2D& to);

class SlippingBase {
 public:
  // The base starts at `start` (world frame) with its encoders at `encoder_start` (odometry
  // frame). std::invalid_argument on an OdometrySpec with a non-positive wheel radius, axle
  // length or rate, or a negative slip_std.
  SlippingBase(const Pose2D& start, const Pose2D& encoder_start, const OdometrySpec& odometry,
               uint64_t seed);

  // The encoders read `encoder_pose` at time_us (microseconds, non-decreasing; an earlier time
  // is ignored). The step since the last call is split at odometry period boundaries, each
  // part moved with its period's slip.
  void Advance(int64_t time_us, const Pose2D& encoder_pose);

  const Pose2D& pose() const { return pose_; }
  // Velocities of the truth over the last Advance with a time step (0 before).
  double linear_mps() const { return linear_mps_; }
  double angular_radps() const { return angular_radps_; }

 private:
  void DrawSlip();
  void MoveTruth(double distance_m, double rotation_rad);

  OdometrySpec odometry_;
  std::mt19937_64 rng_;
  Pose2D pose_;
  Pose2D encoder_pose_;
  int64_t time_us_ = 0;
  bool started_ = false;
  int64_t period_us_ = 0;
  int64_t period_end_us_ = 0;
  double left_factor_ = 1.0;   // true travel / encoder travel of each wheel in this period
  double right_factor_ = 1.0;
  double linear_mps_ = 0.0;
  double angular_radps_ = 0.0;
};

}  // namespace slammtt
