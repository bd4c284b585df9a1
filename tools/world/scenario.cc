#include "tools/world/scenario.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace slammtt {

bool ParseSensorOutput(const std::string& text, SensorOutput* output) {
  if (text == "features") {
    *output = SensorOutput::kFeatures;
  } else if (text == "scans") {
    *output = SensorOutput::kScans;
  } else if (text == "both") {
    *output = SensorOutput::kBoth;
  } else {
    return false;
  }
  return true;
}

const char* SensorOutputName(SensorOutput output) {
  switch (output) {
    case SensorOutput::kFeatures:
      return "features";
    case SensorOutput::kScans:
      return "scans";
    case SensorOutput::kBoth:
      return "both";
  }
  return "?";
}

namespace {

// Collects "path: message" lines.
class Problems {
 public:
  void Add(const std::string& path, const std::string& message) {
    lines_.push_back(path + ": " + message);
  }
  void Finite(const std::string& path, double value) {
    if (!std::isfinite(value)) Add(path, "must be a finite number");
  }
  void Positive(const std::string& path, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) Add(path, "must be positive, got " + Text(value));
  }
  void NonNegative(const std::string& path, double value) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      Add(path, "must not be negative, got " + Text(value));
    }
  }
  void Between(const std::string& path, double value, double low, double high) {
    if (!(value >= low && value <= high)) {
      Add(path, "must be within [" + Text(low) + ", " + Text(high) + "], got " + Text(value));
    }
  }
  static std::string Text(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  }
  // Positions stay within a square of 2000 km: far beyond any robot's world, and small
  // enough that nothing overflows.
  void Coordinate(const std::string& path, double value) {
    if (!(std::abs(value) <= kMaxCoordinateM)) {
      Add(path, "must be within +-" + Text(kMaxCoordinateM) + " m, got " + Text(value));
    }
  }
  std::vector<std::string> lines_;
};

constexpr double kMaxMoverSpeedMps = 50.0;
constexpr double kMaxRadiusM = 1000.0;

std::string Indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

}  // namespace

std::vector<std::string> FindScenarioProblems(const Scenario& s) {
  Problems p;
  p.Positive("duration_s", s.duration_s);
  if (s.duration_s > kMaxScenarioDurationS) p.Add("duration_s", "must not exceed 1e6 s");
  if (s.start_utime < 0 || s.start_utime > 4000000000000000000) {
    p.Add("start_utime", "must be within [0, 4e18] us");
  }

  const LaserSpec& l = s.laser;
  if (!(l.fov_deg > 0.0 && l.fov_deg <= 360.0)) {
    p.Add("laser.fov_deg", "must be within (0, 360], got " + Problems::Text(l.fov_deg));
  }
  p.Positive("laser.resolution_deg", l.resolution_deg);
  if (l.resolution_deg > 0.0 && l.fov_deg > 0.0 && l.fov_deg / l.resolution_deg > 100000.0) {
    p.Add("laser.resolution_deg", "gives more than 100000 beams per scan");
  }
  p.NonNegative("laser.min_range_m", l.min_range_m);
  p.Positive("laser.max_range_m", l.max_range_m);
  if (l.max_range_m <= l.min_range_m) p.Add("laser.max_range_m", "must exceed laser.min_range_m");
  p.Between("laser.rate_hz", l.rate_hz, 0.01, 1000.0);
  p.NonNegative("laser.range_noise_m", l.range_noise_m);
  p.Coordinate("laser.mount_a_m", l.mount_a_m);
  p.Coordinate("laser.mount_b_m", l.mount_b_m);

  p.NonNegative("features.range_noise_m", s.features.range_noise_m);
  p.NonNegative("features.bearing_noise_deg", s.features.bearing_noise_deg);
  p.Between("features.detection_probability", s.features.detection_probability, 0.0, 1.0);

  const OdometrySpec& o = s.odometry;
  p.Between("odometry.rate_hz", o.rate_hz, 0.01, 1000.0);
  p.Positive("odometry.wheel_radius_m", o.wheel_radius_m);
  p.Positive("odometry.axle_length_m", o.axle_length_m);
  p.NonNegative("odometry.encoder_noise_rad", o.encoder_noise_rad);
  p.NonNegative("odometry.slip_std", o.slip_std);
  p.Between("odometry.left_slip_bias", o.left_slip_bias, -0.5, 0.5);
  p.Between("odometry.right_slip_bias", o.right_slip_bias, -0.5, 0.5);

  const RobotMotionSpec& r = s.robot;
  p.Coordinate("robot.start.x_m", r.start.x_m);
  p.Coordinate("robot.start.y_m", r.start.y_m);
  p.Finite("robot.start.heading_deg", r.start.heading_rad);
  for (size_t i = 0; i < r.profile.size(); ++i) {
    const std::string path = Indexed("robot.profile", i);
    p.Positive(path + ".duration_s", r.profile[i].duration_s);
    if (r.profile[i].duration_s > kMaxScenarioDurationS) {
      p.Add(path + ".duration_s", "must not exceed 1e6 s");
    }
    p.Between(path + ".linear_mps", r.profile[i].linear_mps, -kMaxRobotSpeedMps, kMaxRobotSpeedMps);
    if (!(std::abs(r.profile[i].angular_radps) <= 100.0)) {
      p.Add(path + ".angular_degps", "must be within +-5729 deg/s (100 rad/s)");
    }
  }
  if (!r.waypoints.empty()) {
    if (!r.profile.empty()) p.Add("robot", "give either profile or waypoints, not both");
    if (!(r.speed_mps > 0.0 && r.speed_mps <= kMaxRobotSpeedMps)) {
      p.Add("robot.speed_mps", "must be within (0, " + Problems::Text(kMaxRobotSpeedMps) +
                                   "] m/s, got " + Problems::Text(r.speed_mps));
    }
    p.Positive("robot.max_angular_degps", r.max_angular_radps);
    p.Positive("robot.turn_gain_per_s", r.turn_gain_per_s);
    p.Positive("robot.waypoint_tolerance_m", r.waypoint_tolerance_m);
    for (size_t i = 0; i < r.waypoints.size(); ++i) {
      p.Coordinate(Indexed("robot.waypoints", i),
                   std::max(std::abs(r.waypoints[i].x_m), std::abs(r.waypoints[i].y_m)));
    }
  }

  std::set<int64_t> ids;
  auto check_id = [&](const std::string& path, int64_t id) {
    if (!ids.insert(id).second) p.Add(path + ".id", "duplicate object id " + std::to_string(id));
  };
  for (size_t i = 0; i < s.statics.size(); ++i) {
    const std::string path = Indexed("statics", i);
    const StaticObjectSpec& o2 = s.statics[i];
    check_id(path, o2.id);
    p.Coordinate(path + ".x_m", o2.x_m);
    p.Coordinate(path + ".y_m", o2.y_m);
    p.Positive(path + ".radius_m", o2.radius_m);
    if (o2.radius_m > kMaxRadiusM) p.Add(path + ".radius_m", "must not exceed 1000 m");
  }
  for (size_t i = 0; i < s.movers.size(); ++i) {
    const std::string path = Indexed("movers", i);
    const MoverSpec& m = s.movers[i];
    check_id(path, m.id);
    p.Positive(path + ".radius_m", m.radius_m);
    if (m.radius_m > kMaxRadiusM) p.Add(path + ".radius_m", "must not exceed 1000 m");
    p.NonNegative(path + ".appear_s", m.appear_s);
    if (m.appear_s > kMaxScenarioDurationS) p.Add(path + ".appear_s", "must not exceed 1e6 s");
    if (!(m.disappear_s > m.appear_s)) p.Add(path + ".disappear_s", "must be after appear_s");
    switch (m.kind) {
      case MoverKind::kConstantVelocity:
        p.Coordinate(path + ".start", std::max(std::abs(m.start_x_m), std::abs(m.start_y_m)));
        if (!(std::hypot(m.vx_mps, m.vy_mps) <= kMaxMoverSpeedMps)) {
          p.Add(path + ".velocity_mps", "speed must not exceed 50 m/s");
        }
        break;
      case MoverKind::kWaypoints:
        p.Positive(path + ".speed_mps", m.speed_mps);
        if (m.speed_mps > kMaxMoverSpeedMps) p.Add(path + ".speed_mps", "must not exceed 50 m/s");
        if (m.waypoints.empty()) p.Add(path + ".waypoints", "needs at least one waypoint");
        for (size_t k = 0; k < m.waypoints.size(); ++k) {
          const std::string wp = Indexed(path + ".waypoints", k);
          p.Coordinate(wp, std::max(std::abs(m.waypoints[k].x_m), std::abs(m.waypoints[k].y_m)));
          p.NonNegative(wp + ".wait_s", m.waypoints[k].wait_s);
          if (m.waypoints[k].wait_s > kMaxScenarioDurationS) {
            p.Add(wp + ".wait_s", "must not exceed 1e6 s");
          }
        }
        if (m.at_end == PathEnd::kLoop && m.waypoints.size() < 2) {
          p.Add(path + ".at_end", "loop needs at least two waypoints");
        }
        break;
      case MoverKind::kTrajectory:
        if (m.trajectory.empty()) p.Add(path + ".trajectory", "needs at least one point");
        for (size_t k = 0; k < m.trajectory.size(); ++k) {
          const std::string tp = Indexed(path + ".trajectory", k);
          p.Coordinate(tp, std::max(std::abs(m.trajectory[k].x_m), std::abs(m.trajectory[k].y_m)));
          if (!(std::abs(m.trajectory[k].t_s) <= 1e9)) p.Add(tp + ".t_s", "must be within +-1e9 s");
          if (k > 0 && !(m.trajectory[k].t_s > m.trajectory[k - 1].t_s)) {
            p.Add(tp + ".t_s", "times must increase strictly, got " +
                                   Problems::Text(m.trajectory[k].t_s) + " after " +
                                   Problems::Text(m.trajectory[k - 1].t_s));
          }
        }
        break;
      case MoverKind::kRandomWalk: {
        const RandomWalkSpec& w = m.random_walk;
        p.Positive(path + ".speed_mps", m.speed_mps);
        if (m.speed_mps > kMaxMoverSpeedMps) p.Add(path + ".speed_mps", "must not exceed 50 m/s");
        p.Finite(path + ".heading_deg", w.heading_rad);
        p.Positive(path + ".mean_leg_s", w.mean_leg_s);
        p.Between(path + ".max_turn_deg", w.max_turn_rad * 180.0 / M_PI, 0.0, 180.0 + 1e-9);
        p.Between(path + ".reverse_probability", w.reverse_probability, 0.0, 1.0);
        const double area_extent_m =
            std::max({std::abs(w.area_min_x_m), std::abs(w.area_min_y_m),
                      std::abs(w.area_max_x_m), std::abs(w.area_max_y_m)});
        if (!(w.area_max_x_m > w.area_min_x_m && w.area_max_y_m > w.area_min_y_m)) {
          p.Add(path + ".area", "needs min_x < max_x and min_y < max_y");
        } else if (!(area_extent_m <= kMaxCoordinateM)) {
          p.Coordinate(path + ".area", area_extent_m);
        } else if (!(m.start_x_m >= w.area_min_x_m && m.start_x_m <= w.area_max_x_m &&
                     m.start_y_m >= w.area_min_y_m && m.start_y_m <= w.area_max_y_m)) {
          p.Add(path + ".start", "must lie inside the area");
        }
        break;
      }
    }
  }
  return p.lines_;
}

}  // namespace slammtt
