// A small point-feature world for the estimator's own unit tests and benchmarks: a robot
// driven by a velocity schedule, static points and movers with piecewise-constant velocities,
// odometry integrated by eq. 1 from noisy increments, and a range-bearing sensor with the
// paper's noise (section 5.1). It is deliberately simpler than tools/world (no ray casting, no
// scan segmentation) so that a test can state exactly what the estimator saw.
// Pure and deterministic: the world owns a std::mt19937_64 seeded from its options.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "estimator/estimator.h"

namespace slammtt::testing {

// Velocity of an object until `until_s` (seconds since the start of the world).
struct VelocitySegment {
  double until_s = 1e18;
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
};

struct WorldObject {
  int64_t id = 0;
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();
  std::vector<VelocitySegment> segments;  // empty: never moves
  bool mover = false;                     // ground-truth class (a mover may stand still)
  double visible_from_s = 0.0;            // exists from this time
  double visible_until_s = 1e18;          // and until this time
};

struct PointWorldOptions {
  double scan_period_s = 0.125;           // paper 5.1: 8 scans per second
  double odometry_period_s = 0.025;
  double range_sigma_m = 0.2;             // paper 5.1
  double bearing_sigma_rad = 2.0 * M_PI / 180.0;
  double max_range_m = 30.0;
  double field_of_view_rad = M_PI;        // paper S1: 180 degrees
  double detection_probability = 1.0;
  bool features_carry_covariance = true;  // else features have zero variances (defaults used)
  SensorMount sensor;
  double wheel_noise_per_sqrt_m = 0.02;   // std of each distance increment per sqrt(m)
  double turn_noise_per_sqrt_m = 0.01;    // heading std per sqrt(m travelled) [rad]
  uint64_t seed = 1;
};

// Robot linear and angular velocity at time t_s.
using RobotCommand = std::function<Eigen::Vector2d(double t_s)>;

struct TruthObject {
  int64_t id = 0;
  Eigen::Vector2d position_m;
  Eigen::Vector2d velocity_mps;
  bool mover = false;
};

struct WorldFrame {
  int64_t utime = 0;
  std::vector<OdometryReading> odometry;  // readings since the previous frame
  ScanInput scan;
  std::vector<int64_t> feature_truth_ids; // object id of each feature
  Eigen::Vector3d true_pose = Eigen::Vector3d::Zero();
  Eigen::Vector3d odometry_pose = Eigen::Vector3d::Zero();  // dead reckoning at the scan
  std::vector<TruthObject> objects;       // every object that exists now
};

class PointWorld {
 public:
  PointWorld(const PointWorldOptions& options, RobotCommand command,
             std::vector<WorldObject> objects);

  // Advances one scan period and returns what happened.
  WorldFrame Next();
  double time_s() const { return time_s_; }

 private:
  Eigen::Vector2d ObjectPosition(const WorldObject& object, double t_s) const;
  Eigen::Vector2d ObjectVelocity(const WorldObject& object, double t_s) const;

  PointWorldOptions options_;
  RobotCommand command_;
  std::vector<WorldObject> objects_;
  std::mt19937_64 rng_;
  double time_s_ = 0.0;
  double next_odometry_s_ = 0.0;
  int64_t frames_ = 0;
  Eigen::Vector3d pose_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d odometry_pose_ = Eigen::Vector3d::Zero();
};

// Robot poses and object positions of a world with `landmarks` static points and `movers`
// walkers spread around a robot that drives slowly in a circle: the benchmark's crowded scene.
std::vector<WorldObject> CrowdedScene(int landmarks, int movers, double radius_m, uint64_t seed);

}  // namespace slammtt::testing
