#include "tools/world/slipping_base.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/world/odometry_model.h"
#include "tools/world/portable_random.h"

namespace slammtt {

ArcStep ArcStepBetween(const Pose2D& from, const Pose2D& to) {
  const double dx = to.x_m - from.x_m;
  const double dy = to.y_m - from.y_m;
  const double rotation = WrapAngle(to.heading_rad - from.heading_rad);
  // On an arc the chord points along the mean heading; its length is 2 R sin(rotation / 2).
  const double mean_heading = from.heading_rad + 0.5 * rotation;
  const double along = dx * std::cos(mean_heading) + dy * std::sin(mean_heading);
  const double chord = std::hypot(dx, dy);
  const double half = 0.5 * rotation;
  const double arc_per_chord = std::abs(half) < 1e-9 ? 1.0 : half / std::sin(half);
  return ArcStep{std::copysign(chord * arc_per_chord, along), rotation};
}

SlippingBase::SlippingBase(const Pose2D& start, const Pose2D& encoder_start,
                           const OdometrySpec& odometry, uint64_t seed)
    : odometry_(odometry), rng_(seed), pose_(start), encoder_pose_(encoder_start) {
  if (!(odometry.wheel_radius_m > 0.0) || !(odometry.axle_length_m > 0.0) ||
      !(odometry.rate_hz > 0.0) || !(odometry.slip_std >= 0.0)) {
    throw std::invalid_argument(
        "SlippingBase: wheel radius, axle length and rate must be positive, slip_std >= 0");
  }
  pose_.heading_rad = WrapAngle(pose_.heading_rad);
  period_us_ = std::max<int64_t>(1, std::llround(1e6 / odometry.rate_hz));
}

void SlippingBase::DrawSlip() {
  const double left = 1.0 + odometry_.left_slip_bias + GaussianNoise(rng_, odometry_.slip_std);
  const double right = 1.0 + odometry_.right_slip_bias + GaussianNoise(rng_, odometry_.slip_std);
  // A factor near 0 would make a wheel's truth unbounded; slip is a few percent.
  left_factor_ = 1.0 / std::max(left, 0.1);
  right_factor_ = 1.0 / std::max(right, 0.1);
}

void SlippingBase::MoveTruth(double distance_m, double rotation_rad) {
  const WheelIncrements counted = WheelIncrementsForMotion(
      distance_m, rotation_rad, odometry_.wheel_radius_m, odometry_.axle_length_m);
  const double r = odometry_.wheel_radius_m;
  const double left_m = counted.left_rad * r * left_factor_;
  const double right_m = counted.right_rad * r * right_factor_;
  // The true step as one arc: MoveUnicycle over 1 s with speed = distance, rate = rotation.
  pose_ = MoveUnicycle(pose_, 0.5 * (left_m + right_m),
                       (right_m - left_m) / odometry_.axle_length_m, 1.0);
}

void SlippingBase::Advance(int64_t time_us, const Pose2D& encoder_pose) {
  if (!started_) {
    started_ = true;
    time_us_ = time_us;
    period_end_us_ = time_us + period_us_;
    DrawSlip();
  }
  if (time_us < time_us_) return;
  const Pose2D before = pose_;
  const ArcStep step = ArcStepBetween(encoder_pose_, encoder_pose);
  const int64_t span_us = time_us - time_us_;
  int64_t at_us = time_us_;
  while (at_us < time_us) {
    // The part of this step within the current slip period (the encoder motion is spread
    // evenly over the step's time: steps are a few milliseconds).
    const int64_t part_end_us = std::min(time_us, period_end_us_);
    const double share = static_cast<double>(part_end_us - at_us) / static_cast<double>(span_us);
    MoveTruth(step.distance_m * share, step.rotation_rad * share);
    at_us = part_end_us;
    if (at_us >= period_end_us_) {
      period_end_us_ += period_us_;
      DrawSlip();
    }
  }
  if (span_us == 0 && (step.distance_m != 0.0 || step.rotation_rad != 0.0)) {
    MoveTruth(step.distance_m, step.rotation_rad);
  }
  if (span_us > 0) {
    const double dt_s = static_cast<double>(span_us) * 1e-6;
    const ArcStep truth = ArcStepBetween(before, pose_);
    linear_mps_ = truth.distance_m / dt_s;
    angular_radps_ = truth.rotation_rad / dt_s;
  }
  encoder_pose_ = encoder_pose;
  time_us_ = time_us;
}

}  // namespace slammtt
