#include "tools/world/scenario.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "tools/world/scenario_options.h"

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

const char* ObjectKindName(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kWall:
      return "wall";
    case ObjectKind::kFurniture:
      return "furniture";
    case ObjectKind::kPost:
      return "post";
    case ObjectKind::kDisc:
      return "disc";
    case ObjectKind::kPerson:
      return "person";
    case ObjectKind::kLeg:
      return "leg";
  }
  return "?";
}

bool ParseMoverBody(const std::string& text, MoverBody* body) {
  if (text == "discs" || text == "disc") {
    *body = MoverBody::kDisc;
  } else if (text == "legs") {
    *body = MoverBody::kLegs;
  } else {
    return false;
  }
  return true;
}

int StaticIdCount(const StaticObjectSpec& spec) {
  return spec.shape == StaticShape::kLegs ? 4 : 1;
}

int64_t LegId(int64_t person_id, int leg) { return 10 * person_id + 1 + leg; }

MoverBody BodyOf(const Scenario& scenario, const MoverSpec& mover) {
  return mover.body.value_or(scenario.people);
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
// Bounds on the static world's size: every beam is tested against every circle and segment.
constexpr size_t kMaxVertices = 100000;
constexpr size_t kMaxStaticObjects = 100000;
// Person ids stay within this bound so that their legs' ids (10 * id + 1, + 2) cannot overflow.
constexpr int64_t kMaxPersonId = 100000000000000000;
constexpr double kMaxRadiusM = 1000.0;

// scattered_landmarks: ranges, a path to scatter along, room in the static-object bound, and
// ids apart from every static object's (movers are checked against the statics' ids anyway).
void FindScatteredLandmarkProblems(const Scenario& s, Problems* p) {
  const ScatteredLandmarksSpec& g = s.scattered_landmarks;
  const std::string path = "scattered_landmarks";
  if (g.count < 0 || static_cast<size_t>(g.count) + s.statics.size() > kMaxStaticObjects) {
    p->Add(path + ".count", "must be within [0, 100000] with the statics, got " +
                                std::to_string(g.count));
    return;
  }
  if (g.count == 0) return;
  if (s.robot.waypoints.size() < 2) {
    p->Add(path, "needs a robot path of at least two waypoints to scatter along");
  }
  p->Between(path + ".max_offset_m", g.max_offset_m, 0.0, 1000.0);
  if (!(g.min_offset_m > 0.0 && g.min_offset_m < g.max_offset_m)) {
    p->Add(path + ".min_offset_m", "must be within (0, max_offset_m), got " +
                                       Problems::Text(g.min_offset_m));
  }
  p->Between(path + ".min_spacing_m", g.min_spacing_m, 0.0, 100.0);
  if (!(g.radius_m > 0.0 && g.radius_m <= 10.0)) {
    p->Add(path + ".radius_m", "must be within (0, 10], got " + Problems::Text(g.radius_m));
  }
  if (!(std::abs(g.first_id) <= kMaxPersonId)) {
    p->Add(path + ".first_id", "must be within +-1e17");
    return;
  }
  if (g.first_id == 0) return;  // after the statics' ids
  const int64_t last_id = g.first_id + g.count - 1;
  for (size_t i = 0; i < s.statics.size(); ++i) {
    const int64_t id = s.statics[i].id;
    if (id + StaticIdCount(s.statics[i]) - 1 >= g.first_id && id <= last_id) {
      p->Add(path + ".first_id", "ids " + std::to_string(g.first_id) + ".." +
                                     std::to_string(last_id) + " overlap statics[" +
                                     std::to_string(i) + "]'s id " + std::to_string(id));
      return;
    }
  }
}

std::string Indexed(const std::string& list, size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

}  // namespace

namespace {

void FindShapeProblems(const std::string& path, const StaticObjectSpec& o, Problems* problems) {
  Problems& p = *problems;
  switch (o.shape) {
    case StaticShape::kCircle:
      p.Coordinate(path + ".x_m", o.x_m);
      p.Coordinate(path + ".y_m", o.y_m);
      p.Positive(path + ".radius_m", o.radius_m);
      if (o.radius_m > kMaxRadiusM) p.Add(path + ".radius_m", "must not exceed 1000 m");
      return;
    case StaticShape::kBox:
    case StaticShape::kLegs:
      p.Coordinate(path + ".center", std::max(std::abs(o.x_m), std::abs(o.y_m)));
      p.Positive(path + ".size_m", std::min(o.size_x_m, o.size_y_m));
      if (std::max(o.size_x_m, o.size_y_m) > kMaxRadiusM) {
        p.Add(path + ".size_m", "must not exceed 1000 m");
      }
      p.Finite(path + ".heading_deg", o.heading_rad);
      if (o.shape == StaticShape::kLegs) {
        p.Positive(path + ".leg_radius_m", o.leg_radius_m);
        if (o.leg_radius_m * 2.0 > std::min(o.size_x_m, o.size_y_m)) {
          p.Add(path + ".leg_radius_m", "legs must fit inside size_m");
        }
      }
      return;
    case StaticShape::kPolygon:
    case StaticShape::kPolyline:
      break;
  }
  const bool closed = o.shape == StaticShape::kPolygon;
  const size_t n = o.vertices.size();
  if (n > kMaxVertices) {
    p.Add(path + ".vertices", "more than 100000 vertices");
    return;
  }
  if (o.openings.size() > kMaxVertices) {
    p.Add(path + ".openings", "more than 100000 openings");
    return;
  }
  if (n < (closed ? 3u : 2u)) {
    p.Add(path + ".vertices", closed ? "a polygon needs at least 3 vertices"
                                     : "a polyline needs at least 2 vertices");
    return;
  }
  bool coordinates_ok = true;
  for (size_t k = 0; k < n; ++k) {
    const double extent = std::max(std::abs(o.vertices[k].x_m), std::abs(o.vertices[k].y_m));
    if (!(extent <= kMaxCoordinateM)) {
      p.Coordinate(Indexed(path + ".vertices", k), extent);
      coordinates_ok = false;
    }
  }
  if (!coordinates_ok) return;
  const size_t sides = closed ? n : n - 1;
  for (size_t k = 0; k < sides; ++k) {
    const PlanarPoint& a = o.vertices[k];
    const PlanarPoint& b = o.vertices[(k + 1) % n];
    if (a.x_m == b.x_m && a.y_m == b.y_m) {
      p.Add(Indexed(path + ".vertices", (k + 1) % n), "repeats the vertex before it");
    }
  }
  for (size_t k = 0; k < o.openings.size(); ++k) {
    const std::string opening = Indexed(path + ".openings", k);
    const WallOpening& w = o.openings[k];
    if (w.side < 0 || static_cast<size_t>(w.side) >= sides) {
      p.Add(opening, "side " + std::to_string(w.side) + " does not exist (sides 0-" +
                         std::to_string(sides - 1) + ")");
      continue;
    }
    const PlanarPoint& a = o.vertices[static_cast<size_t>(w.side)];
    const PlanarPoint& b = o.vertices[(static_cast<size_t>(w.side) + 1) % n];
    const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    if (!(w.offset_m >= 0.0) || !(w.width_m > 0.0) || !(w.offset_m + w.width_m <= length)) {
      p.Add(opening, "must lie within side " + std::to_string(w.side) + " (length " +
                         Problems::Text(length) + " m) with offset >= 0 and width > 0");
      continue;
    }
    for (size_t j = 0; j < k; ++j) {
      const WallOpening& v = o.openings[j];
      if (v.side == w.side && w.offset_m < v.offset_m + v.width_m &&
          v.offset_m < w.offset_m + w.width_m) {
        p.Add(opening, "overlaps opening " + std::to_string(j));
      }
    }
  }
}

}  // namespace

std::vector<std::string> FindScenarioProblems(const Scenario& s) {
  Problems p;
  // Every setting within its range (scenario_options.h), then the conditions between them.
  const auto [setting, problem] = FindScenarioSettingsProblem(s);
  if (!setting.empty()) p.Add(setting, problem);

  const LaserSpec& l = s.laser;
  if (l.resolution_deg > 0.0 && l.fov_deg > 0.0 && l.fov_deg / l.resolution_deg > 100000.0) {
    p.Add("laser.resolution_deg", "gives more than 100000 beams per scan");
  }
  if (l.max_range_m <= l.min_range_m) p.Add("laser.max_range_m", "must exceed laser.min_range_m");
  const LaserArtefactSpec& a = l.artefacts;
  if (a.sample_rate_hz > 0.0 && a.sample_rate_hz < 10.0) {
    p.Add("laser.sample_rate_hz",
          "must be 0 (even beams) or within [10, 1e6], got " + Problems::Text(a.sample_rate_hz));
  } else if (a.sample_rate_hz > 0.0 && a.sample_rate_hz / l.rate_hz > 100000.0) {
    p.Add("laser.sample_rate_hz", "gives more than 100000 beams per scan");
  } else if (a.sample_rate_hz > 0.0 && l.fov_deg < 360.0) {
    p.Add("laser.sample_rate_hz", "sampled beam angles need a 360-degree laser (fov_deg 360)");
  }

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
    for (size_t i = 0; i < r.waypoints.size(); ++i) {
      p.Coordinate(Indexed("robot.waypoints", i),
                   std::max(std::abs(r.waypoints[i].x_m), std::abs(r.waypoints[i].y_m)));
    }
  }

  std::set<int64_t> ids;
  auto check_id = [&](const std::string& path, int64_t id) {
    if (!ids.insert(id).second) p.Add(path + ".id", "duplicate object id " + std::to_string(id));
  };
  if (s.statics.size() > kMaxStaticObjects) p.Add("statics", "more than 100000 static objects");
  for (size_t i = 0; i < s.statics.size() && i < kMaxStaticObjects; ++i) {
    const std::string path = Indexed("statics", i);
    const StaticObjectSpec& o2 = s.statics[i];
    if (!(std::abs(o2.id) <= kMaxPersonId)) {
      p.Add(path + ".id", "must be within +-1e17");
    } else {
      for (int k = 0; k < StaticIdCount(o2); ++k) check_id(path, o2.id + k);
    }
    if (o2.kind != ObjectKind::kWall && o2.kind != ObjectKind::kFurniture &&
        o2.kind != ObjectKind::kPost) {
      p.Add(path + ".kind", "a static object is a wall, furniture or a post");
    }
    p.Between(path + ".dropout_probability", o2.dropout_probability, 0.0, 1.0);
    FindShapeProblems(path, o2, &p);
  }
  FindScatteredLandmarkProblems(s, &p);
  for (size_t i = 0; i < s.movers.size(); ++i) {
    const std::string path = Indexed("movers", i);
    const MoverSpec& m = s.movers[i];
    check_id(path, m.id);
    if (BodyOf(s, m) == MoverBody::kLegs) {
      if (!(std::abs(m.id) <= kMaxPersonId)) {
        p.Add(path + ".id", "a person's id must be within +-1e17");
      } else {
        check_id(path, LegId(m.id, 0));
        check_id(path, LegId(m.id, 1));
      }
    }
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
