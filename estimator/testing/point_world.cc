#include "estimator/testing/point_world.h"

#include <cmath>

#include "estimator/angle.h"

namespace slammtt::testing {

PointWorld::PointWorld(const PointWorldOptions& options, RobotCommand command,
                       std::vector<WorldObject> objects)
    : options_(options), command_(std::move(command)), objects_(std::move(objects)),
      rng_(options.seed) {}

Eigen::Vector2d PointWorld::ObjectPosition(const WorldObject& object, double t_s) const {
  Eigen::Vector2d position = object.start_m;
  double from = 0.0;
  for (const VelocitySegment& segment : object.segments) {
    const double to = std::min(segment.until_s, t_s);
    if (to > from) position += (to - from) * segment.velocity_mps;
    from = segment.until_s;
    if (from >= t_s) break;
  }
  return position;
}

Eigen::Vector2d PointWorld::ObjectVelocity(const WorldObject& object, double t_s) const {
  for (const VelocitySegment& segment : object.segments) {
    if (t_s < segment.until_s) return segment.velocity_mps;
  }
  return Eigen::Vector2d::Zero();
}

WorldFrame PointWorld::Next() {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  WorldFrame frame;
  const double end = static_cast<double>(++frames_) * options_.scan_period_s;
  // Integrate the robot in small steps; odometry readings at their own period.
  const double step = 0.005;
  while (time_s_ < end - 1e-9) {
    const double dt = std::min(step, end - time_s_);
    const Eigen::Vector2d command = command_(time_s_);
    const OdometryIncrement truth{command(0) * dt, command(1) * dt};
    pose_ = PredictRobotPose(pose_, truth);
    const double distance = std::abs(truth.distance_m);
    const OdometryIncrement measured{
        truth.distance_m + options_.wheel_noise_per_sqrt_m * std::sqrt(distance) * normal(rng_),
        truth.rotation_rad + options_.turn_noise_per_sqrt_m * std::sqrt(distance) * normal(rng_)};
    odometry_pose_ = PredictRobotPose(odometry_pose_, measured);
    time_s_ += dt;
    if (time_s_ >= next_odometry_s_ - 1e-9) {
      next_odometry_s_ += options_.odometry_period_s;
      OdometryReading reading;
      reading.utime = static_cast<int64_t>(std::llround(time_s_ * 1e6));
      reading.pose = odometry_pose_;
      reading.linear_mps = command(0);
      reading.angular_radps = command(1);
      frame.odometry.push_back(reading);
    }
  }
  frame.utime = static_cast<int64_t>(std::llround(time_s_ * 1e6));
  frame.scan.utime = frame.utime;
  frame.true_pose = pose_;
  frame.odometry_pose = odometry_pose_;
  for (const WorldObject& object : objects_) {
    if (time_s_ < object.visible_from_s || time_s_ > object.visible_until_s) continue;
    TruthObject truth{object.id, ObjectPosition(object, time_s_), ObjectVelocity(object, time_s_),
                      object.mover};
    frame.objects.push_back(truth);
    const Eigen::Vector2d z = PredictRangeBearing(pose_, truth.position_m, options_.sensor);
    if (z(0) > options_.max_range_m || std::abs(z(1)) > 0.5 * options_.field_of_view_rad) continue;
    if (uniform(rng_) > options_.detection_probability) continue;
    FeatureReading feature;
    feature.range_m = std::max(0.05, z(0) + options_.range_sigma_m * normal(rng_));
    feature.bearing_rad = WrapAngle(z(1) + options_.bearing_sigma_rad * normal(rng_));
    if (options_.features_carry_covariance) {
      feature.range_var_m2 = options_.range_sigma_m * options_.range_sigma_m;
      feature.bearing_var_rad2 = options_.bearing_sigma_rad * options_.bearing_sigma_rad;
    }
    frame.scan.features.push_back(feature);
    frame.feature_truth_ids.push_back(object.id);
  }
  return frame;
}

std::vector<WorldObject> CrowdedScene(int landmarks, int movers, double radius_m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<WorldObject> objects;
  int64_t id = 1;
  for (int k = 0; k < landmarks; ++k) {
    WorldObject o;
    o.id = id++;
    const double a = angle(rng);
    const double r = 3.0 + (radius_m - 3.0) * std::sqrt(unit(rng));
    o.start_m = Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    objects.push_back(o);
  }
  for (int k = 0; k < movers; ++k) {
    WorldObject o;
    o.id = id++;
    o.mover = true;
    const double a = angle(rng);
    const double r = 3.0 + 0.5 * (radius_m - 3.0) * unit(rng);
    o.start_m = Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    const double heading = angle(rng);
    const double speed = 0.5 + unit(rng);
    o.segments.push_back({1e18, speed * Eigen::Vector2d(std::cos(heading), std::sin(heading))});
    objects.push_back(o);
  }
  return objects;
}

}  // namespace slammtt::testing
