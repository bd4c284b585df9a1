#include "tools/world/odometry_model.h"

#include <cmath>

#include "tools/world/portable_random.h"

namespace slammtt {

WheelIncrements WheelIncrementsForMotion(double distance_m, double rotation_rad,
                                         double wheel_radius_m, double axle_length_m) {
  const double half_track = 0.5 * axle_length_m * rotation_rad;
  return WheelIncrements{(distance_m - half_track) / wheel_radius_m,
                         (distance_m + half_track) / wheel_radius_m};
}

Pose2D IntegrateWheelIncrements(const Pose2D& pose, const WheelIncrements& increments,
                                double wheel_radius_m, double axle_length_m) {
  // Omega_r dt and Omega_d dt of eq. 1.
  const double distance = 0.5 * (increments.right_rad + increments.left_rad) * wheel_radius_m;
  const double rotation =
      (increments.right_rad - increments.left_rad) * wheel_radius_m / axle_length_m;
  const double heading = pose.heading_rad + rotation;
  return Pose2D{pose.x_m + distance * std::cos(heading), pose.y_m + distance * std::sin(heading),
                WrapAngle(heading)};
}

namespace {

double MeasureWheel(double truth, double bias, const OdometrySpec& spec, std::mt19937_64& rng) {
  if (truth == 0.0) return 0.0;  // a wheel standing still reads nothing
  const double slip = GaussianNoise(rng, spec.slip_std);
  const double noise = GaussianNoise(rng, spec.encoder_noise_rad);
  return truth * (1.0 + bias + slip) + noise;
}

}  // namespace

WheelIncrements MeasureWheelIncrements(const WheelIncrements& truth, const OdometrySpec& spec,
                                       std::mt19937_64& rng) {
  WheelIncrements measured;
  measured.left_rad = MeasureWheel(truth.left_rad, spec.left_slip_bias, spec, rng);
  measured.right_rad = MeasureWheel(truth.right_rad, spec.right_slip_bias, spec, rng);
  return measured;
}

OdometryIntegrator::OdometryIntegrator(const OdometrySpec& spec) : spec_(spec) {}

OdometryReading OdometryIntegrator::Start(int64_t time_us) {
  pose_ = Pose2D{};
  last_time_us_ = time_us;
  sequence_ = 0;
  OdometryReading reading;
  reading.time_us = time_us;
  reading.sequence = sequence_++;
  return reading;
}

OdometryReading OdometryIntegrator::Update(int64_t time_us, double distance_m, double rotation_rad,
                                           std::mt19937_64& rng) {
  const WheelIncrements truth =
      WheelIncrementsForMotion(distance_m, rotation_rad, spec_.wheel_radius_m, spec_.axle_length_m);
  const WheelIncrements measured = MeasureWheelIncrements(truth, spec_, rng);
  pose_ = IntegrateWheelIncrements(pose_, measured, spec_.wheel_radius_m, spec_.axle_length_m);

  OdometryReading reading;
  reading.time_us = time_us;
  reading.sequence = sequence_++;
  reading.pose = pose_;
  const double dt = static_cast<double>(time_us - last_time_us_) * 1e-6;
  if (dt > 0.0) {
    reading.left_wheel_mps = measured.left_rad * spec_.wheel_radius_m / dt;
    reading.right_wheel_mps = measured.right_rad * spec_.wheel_radius_m / dt;
    reading.linear_mps = 0.5 * (reading.left_wheel_mps + reading.right_wheel_mps);
    reading.angular_radps =
        (reading.right_wheel_mps - reading.left_wheel_mps) / spec_.axle_length_m;
  }
  last_time_us_ = time_us;
  return reading;
}

}  // namespace slammtt
