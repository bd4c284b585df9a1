#include "tools/world/scenario_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "common/number_text.h"
#include "runtime/config_options.h"
#include "tools/world/scenario_options.h"

namespace slammtt {

namespace {

constexpr double kDegToRad = M_PI / 180.0;
// Bound of recorded person ids and of crowd.id_offset, so that their sum (the mover id) cannot
// overflow.
constexpr int64_t kMaxRecordedId = 1000000000000000;

// Remembers where every value came from, so that a problem found after reading (by
// FindScenarioProblems, which knows nothing of files) is reported at its line.
class Locations {
 public:
  // `key` empty: the node itself (a list element).
  void Add(const std::string& path, const Config& node, const std::string& key) {
    entries_.emplace(path, Entry{node, key});
  }
  // Throws ConfigError for "path: message" at the nearest recorded enclosing path.
  [[noreturn]] void Fail(const std::string& problem, const Config& root) const {
    const size_t colon = problem.find(": ");
    const std::string path = problem.substr(0, colon);
    const std::string message = colon == std::string::npos ? problem : problem.substr(colon + 2);
    std::string prefix = path;
    while (!prefix.empty()) {
      const auto it = entries_.find(prefix);
      if (it != entries_.end()) {
        const std::string rest = path.substr(prefix.size());
        const std::string detail =
            rest.empty() ? message : rest.substr(rest[0] == '.' ? 1 : 0) + ": " + message;
        if (it->second.key.empty()) it->second.node.Fail(detail);
        it->second.node.FailKey(it->second.key, detail);
      }
      const size_t cut = prefix.find_last_of(".[");
      prefix = cut == std::string::npos ? std::string() : prefix.substr(0, cut);
    }
    root.Fail(problem);
  }

 private:
  struct Entry {
    Config node;
    std::string key;
  };
  std::map<std::string, Entry> entries_;
};

class ScenarioReader {
 public:
  ScenarioReader(const Config& root, std::string base_dir)
      : root_(root), base_dir_(std::move(base_dir)) {}

  Scenario Read() {
    root_.CheckKeysAmong({"name", "description", "duration_s", "start_utime", "output", "laser",
                          "features", "odometry", "robot", "statics", "scattered_landmarks",
                          "movers", "crowd", "people", "legs"});
    Scenario s;
    s.name = root_.GetString("name", "");
    root_.GetString("description", "");  // for people only
    // The settings through their schemas (scenario_options.h); the robot's geometry below.
    VisitScenarioSections(&s, [this](const std::string& section) -> OptionVisitor* {
      return Section(section);
    });
    for (const char* section : {"laser", "features", "odometry", "legs", "scattered_landmarks"}) {
      root_.Child(section).CheckUnused();
    }
    ReadRobotPath(root_.Child("robot"), &s.robot);
    if (root_.Has("people")) {
      const std::string people = root_.GetString("people", "");
      if (!ParseMoverBody(people, &s.people)) {
        root_.FailKey("people", "expected discs or legs, got \"" + people + "\"");
      }
    }
    const std::vector<Config> statics = root_.Items("statics");
    int64_t next_id = 1;
    for (size_t i = 0; i < statics.size(); ++i) {
      s.statics.push_back(ReadStatic(statics[i], next_id));
      next_id = s.statics.back().id + StaticIdCount(s.statics.back());
    }
    const std::vector<Config> movers = root_.Items("movers");
    for (size_t i = 0; i < movers.size(); ++i) s.movers.push_back(ReadMover(movers[i], i));
    if (root_.Has("crowd")) ReadCrowd(root_.Child("crowd"), &s.movers);

    root_.CheckUnused();
    const std::vector<std::string> problems = FindScenarioProblems(s);
    if (!problems.empty()) locations_.Fail(problems.front(), root_);
    return s;
  }

 private:
  // The reader of a section's settings ("" the top level). Every key of the section is
  // remembered for the conditions FindScenarioProblems reports after reading.
  OptionVisitor* Section(const std::string& section) {
    const Config node = section.empty() ? root_ : root_.Child(section);
    for (const std::string& key : node.Keys()) {
      const bool format = section.empty() ? key != "duration_s" && key != "start_utime"
                                          : section == "robot" && (key == "start" ||
                                                                   key == "profile" ||
                                                                   key == "waypoints");
      if (!format) locations_.Add(Join(node, key), node, key);
    }
    readers_.push_back(std::make_unique<ConfigOptionReader>(node));
    return readers_.back().get();
  }

  double Double(const Config& node, const std::string& key, double fallback) {
    locations_.Add(Join(node, key), node, key);
    return node.GetDouble(key, fallback);
  }
  int64_t Int(const Config& node, const std::string& key, int64_t fallback) {
    locations_.Add(Join(node, key), node, key);
    return node.GetInt(key, fallback);
  }
  // A list of exactly `n` numbers (or n-1 when `optional_last`), e.g. [x_m, y_m].
  std::vector<double> Numbers(const Config& element, size_t n, bool optional_last,
                              const std::string& what) {
    if (!element.IsSequence()) element.Fail("expected " + what);
    const std::vector<double> values = element.AsDoubles();
    if (values.size() != n && !(optional_last && values.size() + 1 == n)) {
      element.Fail("expected " + what + ", got " + std::to_string(values.size()) + " numbers");
    }
    return values;
  }
  std::vector<double> NumbersKey(const Config& node, const std::string& key, size_t n,
                                 const std::string& what) {
    locations_.Add(Join(node, key), node, key);
    if (!node.Has(key)) node.FailKey(key, "missing key");
    const std::vector<double> values = node.GetDoubles(key, {});
    if (values.size() != n) {
      node.FailKey(key, "expected " + what + ", got " + std::to_string(values.size()) + " numbers");
    }
    return values;
  }
  static std::string Join(const Config& node, const std::string& key) {
    return node.Path().empty() ? key : node.Path() + "." + key;
  }

  // `body: disc | legs` of a mover or of the crowd.
  std::optional<MoverBody> Body(const Config& c) {
    if (!c.Has("body")) return std::nullopt;
    MoverBody body = MoverBody::kDisc;
    const std::string text = c.GetString("body", "");
    if (!ParseMoverBody(text, &body)) {
      c.FailKey("body", "expected disc or legs, got \"" + text + "\"");
    }
    return body;
  }

  // The robot's path: start, profile, waypoints (its settings came through the schema).
  void ReadRobotPath(const Config& c, RobotMotionSpec* r) {
    const Config start = c.Child("start");
    start.CheckKeysAmong({"x_m", "y_m", "heading_deg"});
    r->start.x_m = Double(start, "x_m", 0.0);
    r->start.y_m = Double(start, "y_m", 0.0);
    r->start.heading_rad = Double(start, "heading_deg", 0.0) * kDegToRad;
    for (const Config& segment : c.Items("profile")) {
      if (!segment.IsMap()) segment.Fail("expected {duration_s, linear_mps, angular_degps}");
      locations_.Add(segment.Path(), segment, "");
      segment.CheckKeysAmong({"duration_s", "linear_mps", "angular_degps"});
      VelocitySegment v;
      if (!segment.Has("duration_s")) segment.FailKey("duration_s", "missing key");
      v.duration_s = Double(segment, "duration_s", 0.0);
      v.linear_mps = Double(segment, "linear_mps", 0.0);
      v.angular_radps = Double(segment, "angular_degps", 0.0) * kDegToRad;
      r->profile.push_back(v);
    }
    for (const Config& point : c.Items("waypoints")) {
      locations_.Add(point.Path(), point, "");
      const std::vector<double> xy = Numbers(point, 2, false, "[x_m, y_m]");
      r->waypoints.push_back(PlanarPoint{xy[0], xy[1]});
    }
    if (r->profile.empty() && r->waypoints.empty() && c.Has("profile")) {
      c.FailKey("profile", "must not be empty");
    }
    c.CheckUnused();
  }

  StaticObjectSpec ReadStatic(const Config& c, int64_t default_id) {
    if (!c.IsMap()) c.Fail("expected {id, x_m, y_m, radius_m} or {type: ..., ...}");
    locations_.Add(c.Path(), c, "");
    StaticObjectSpec o;
    const std::string type = c.GetString("type", "circle");
    std::vector<std::string> keys = {"id", "type", "kind", "dropout_probability"};
    if (type == "circle") {
      o.shape = StaticShape::kCircle;
      keys.insert(keys.end(), {"x_m", "y_m", "radius_m"});
    } else if (type == "polygon" || type == "polyline") {
      o.shape = type == "polygon" ? StaticShape::kPolygon : StaticShape::kPolyline;
      o.kind = ObjectKind::kWall;
      keys.insert(keys.end(), {"vertices", "openings"});
    } else if (type == "box") {
      o.shape = StaticShape::kBox;
      o.kind = ObjectKind::kFurniture;
      keys.insert(keys.end(), {"center", "size_m", "heading_deg"});
    } else if (type == "chair" || type == "table") {
      o.shape = StaticShape::kLegs;
      o.kind = ObjectKind::kFurniture;
      // A chair: 0.45 m square on legs of 0.015 m; a table: 1.2 x 0.8 m on legs of 0.025 m.
      o.size_x_m = type == "chair" ? 0.45 : 1.2;
      o.size_y_m = type == "chair" ? 0.45 : 0.8;
      o.leg_radius_m = type == "chair" ? 0.015 : 0.025;
      keys.insert(keys.end(), {"center", "size_m", "heading_deg", "leg_radius_m"});
    } else {
      c.FailKey("type", "expected circle, polygon, polyline, box, chair or table, got \"" + type +
                            "\"");
    }
    c.CheckKeysAmong(keys);
    o.id = Int(c, "id", default_id);
    if (c.Has("kind")) {
      locations_.Add(Join(c, "kind"), c, "kind");
      const std::string kind = c.GetString("kind", "");
      if (kind == "wall") {
        o.kind = ObjectKind::kWall;
      } else if (kind == "furniture") {
        o.kind = ObjectKind::kFurniture;
      } else if (kind == "post") {
        o.kind = ObjectKind::kPost;
      } else {
        c.FailKey("kind", "expected wall, furniture or post, got \"" + kind + "\"");
      }
    }
    o.dropout_probability = Double(c, "dropout_probability", o.dropout_probability);
    switch (o.shape) {
      case StaticShape::kCircle:
        if (!c.Has("x_m")) c.FailKey("x_m", "missing key");
        if (!c.Has("y_m")) c.FailKey("y_m", "missing key");
        o.x_m = Double(c, "x_m", 0.0);
        o.y_m = Double(c, "y_m", 0.0);
        o.radius_m = Double(c, "radius_m", o.radius_m);
        break;
      case StaticShape::kPolygon:
      case StaticShape::kPolyline: {
        if (!c.Has("vertices")) c.FailKey("vertices", "missing key");
        locations_.Add(Join(c, "vertices"), c, "vertices");
        for (const Config& point : c.Items("vertices")) {
          locations_.Add(point.Path(), point, "");
          const std::vector<double> xy = Numbers(point, 2, false, "[x_m, y_m]");
          o.vertices.push_back(PlanarPoint{xy[0], xy[1]});
        }
        locations_.Add(Join(c, "openings"), c, "openings");
        for (const Config& opening : c.Items("openings")) {
          locations_.Add(opening.Path(), opening, "");
          const std::vector<double> v = Numbers(opening, 3, false, "[side, offset_m, width_m]");
          if (!(v[0] >= 0.0 && v[0] <= 1e6 && v[0] == std::floor(v[0]))) {
            opening.Fail("side must be a whole number >= 0");
          }
          o.openings.push_back(WallOpening{static_cast<int>(v[0]), v[1], v[2]});
        }
        break;
      }
      case StaticShape::kBox:
      case StaticShape::kLegs: {
        const std::vector<double> center = NumbersKey(c, "center", 2, "[x_m, y_m]");
        o.x_m = center[0];
        o.y_m = center[1];
        if (o.shape == StaticShape::kBox || c.Has("size_m")) {
          const std::vector<double> size = NumbersKey(c, "size_m", 2, "[size_x_m, size_y_m]");
          o.size_x_m = size[0];
          o.size_y_m = size[1];
        }
        o.heading_rad = Double(c, "heading_deg", 0.0) * kDegToRad;
        if (o.shape == StaticShape::kLegs) {
          o.leg_radius_m = Double(c, "leg_radius_m", o.leg_radius_m);
        }
        break;
      }
    }
    return o;
  }

  MoverSpec ReadMover(const Config& c, size_t index) {
    if (!c.IsMap()) c.Fail("expected a mapping with type: ...");
    locations_.Add(c.Path(), c, "");
    MoverSpec m;
    if (!c.Has("type")) {
      c.FailKey("type", "missing key (constant_velocity, waypoints, trajectory or random_walk)");
    }
    const std::string type = c.GetString("type", "");
    std::vector<std::string> keys = {"id", "type", "radius_m", "appear_s", "disappear_s", "body"};
    if (type == "constant_velocity") {
      m.kind = MoverKind::kConstantVelocity;
      keys.insert(keys.end(), {"start", "velocity_mps"});
    } else if (type == "waypoints") {
      m.kind = MoverKind::kWaypoints;
      keys.insert(keys.end(), {"waypoints", "speed_mps", "at_end"});
    } else if (type == "trajectory") {
      m.kind = MoverKind::kTrajectory;
      keys.insert(keys.end(), {"trajectory"});
    } else if (type == "random_walk") {
      m.kind = MoverKind::kRandomWalk;
      keys.insert(keys.end(), {"start", "speed_mps", "heading_deg", "mean_leg_s", "max_turn_deg",
                               "reverse_probability", "area"});
    } else {
      c.FailKey("type", "expected constant_velocity, waypoints, trajectory or random_walk, got \"" +
                            type + "\"");
    }
    c.CheckKeysAmong(keys);
    m.id = Int(c, "id", 10000 + static_cast<int64_t>(index));
    m.radius_m = Double(c, "radius_m", m.radius_m);
    m.appear_s = Double(c, "appear_s", m.appear_s);
    if (c.Has("disappear_s")) m.disappear_s = Double(c, "disappear_s", 0.0);
    m.body = Body(c);
    switch (m.kind) {
      case MoverKind::kConstantVelocity: {
        const std::vector<double> start = NumbersKey(c, "start", 2, "[x_m, y_m]");
        const std::vector<double> v = NumbersKey(c, "velocity_mps", 2, "[vx_mps, vy_mps]");
        m.start_x_m = start[0];
        m.start_y_m = start[1];
        m.vx_mps = v[0];
        m.vy_mps = v[1];
        break;
      }
      case MoverKind::kWaypoints: {
        if (!c.Has("waypoints")) c.FailKey("waypoints", "missing key");
        locations_.Add(Join(c, "waypoints"), c, "waypoints");
        for (const Config& point : c.Items("waypoints")) {
          locations_.Add(point.Path(), point, "");
          const std::vector<double> p = Numbers(point, 3, true, "[x_m, y_m] or [x_m, y_m, wait_s]");
          m.waypoints.push_back(MoverWaypoint{p[0], p[1], p.size() == 3 ? p[2] : 0.0});
        }
        m.speed_mps = Double(c, "speed_mps", m.speed_mps);
        locations_.Add(Join(c, "at_end"), c, "at_end");
        const std::string at_end = c.GetString("at_end", "stay");
        if (at_end == "stay") {
          m.at_end = PathEnd::kStay;
        } else if (at_end == "leave") {
          m.at_end = PathEnd::kLeave;
        } else if (at_end == "loop") {
          m.at_end = PathEnd::kLoop;
        } else {
          c.FailKey("at_end", "expected stay, leave or loop, got \"" + at_end + "\"");
        }
        break;
      }
      case MoverKind::kTrajectory: {
        if (!c.Has("trajectory")) c.FailKey("trajectory", "missing key");
        locations_.Add(Join(c, "trajectory"), c, "trajectory");
        for (const Config& point : c.Items("trajectory")) {
          locations_.Add(point.Path(), point, "");
          const std::vector<double> p = Numbers(point, 3, false, "[t_s, x_m, y_m]");
          m.trajectory.push_back(TimedPoint{p[0], p[1], p[2]});
        }
        break;
      }
      case MoverKind::kRandomWalk: {
        const std::vector<double> start = NumbersKey(c, "start", 2, "[x_m, y_m]");
        m.start_x_m = start[0];
        m.start_y_m = start[1];
        m.speed_mps = Double(c, "speed_mps", m.speed_mps);
        RandomWalkSpec& w = m.random_walk;
        w.heading_rad = Double(c, "heading_deg", 0.0) * kDegToRad;
        w.mean_leg_s = Double(c, "mean_leg_s", w.mean_leg_s);
        w.max_turn_rad = Double(c, "max_turn_deg", w.max_turn_rad / kDegToRad) * kDegToRad;
        w.reverse_probability = Double(c, "reverse_probability", w.reverse_probability);
        const std::vector<double> area =
            NumbersKey(c, "area", 4, "[min_x_m, min_y_m, max_x_m, max_y_m]");
        w.area_min_x_m = area[0];
        w.area_min_y_m = area[1];
        w.area_max_x_m = area[2];
        w.area_max_y_m = area[3];
        break;
      }
    }
    return m;
  }

  void ReadCrowd(const Config& c, std::vector<MoverSpec>* movers) {
    c.CheckKeysAmong({"file", "window_s", "rotation_deg", "offset_m", "max_people", "radius_m",
                      "id_offset", "body"});
    const std::optional<MoverBody> body = Body(c);
    if (!c.Has("file")) c.FailKey("file", "missing key");
    const std::string file = c.GetString("file", "");
    const std::filesystem::path path =
        std::filesystem::path(file).is_absolute() ? std::filesystem::path(file)
                                                  : std::filesystem::path(base_dir_) / file;
    CrowdImportSpec spec;
    if (c.Has("window_s")) {
      const std::vector<double> window = NumbersKey(c, "window_s", 2, "[start_s, end_s]");
      if (!(window[1] > window[0])) c.FailKey("window_s", "end must be after start");
      spec.window_start_s = window[0];
      spec.window_end_s = window[1];
    }
    spec.rotation_rad = Double(c, "rotation_deg", 0.0) * kDegToRad;
    if (c.Has("offset_m")) {
      const std::vector<double> offset = NumbersKey(c, "offset_m", 2, "[x_m, y_m]");
      spec.offset_x_m = offset[0];
      spec.offset_y_m = offset[1];
    }
    const int64_t max_people = Int(c, "max_people", 0);
    if (max_people < 0 || max_people > 100000) {
      c.FailKey("max_people", "must be within [0, 100000]");
    }
    spec.max_people = static_cast<int>(max_people);
    spec.radius_m = Double(c, "radius_m", spec.radius_m);
    if (!(spec.radius_m > 0.0)) c.FailKey("radius_m", "must be positive");
    spec.id_offset = Int(c, "id_offset", spec.id_offset);
    if (std::abs(spec.id_offset) > kMaxRecordedId) {
      c.FailKey("id_offset", "must be within +-1e15 (mover id = id_offset + recorded id)");
    }

    std::vector<RecordedTrack> tracks;
    try {
      tracks = ReadRecordedTracks(path.string());
    } catch (const ConfigError& e) {
      c.FailKey("file", e.what());
    }
    const size_t first = movers->size();
    for (MoverSpec& m : MoversFromRecordedTracks(tracks, spec)) {
      m.body = body;
      movers->push_back(std::move(m));
    }
    for (size_t i = first; i < movers->size(); ++i) {
      locations_.Add("movers[" + std::to_string(i) + "]", c, "");
    }
  }

  Config root_;
  std::string base_dir_;
  Locations locations_;
  std::vector<std::unique_ptr<ConfigOptionReader>> readers_;
};

}  // namespace

namespace {

// Config reports its own errors as ConfigError; anything else that might still escape from the
// YAML library or the file system has to name the file too.
Scenario ReadGuarded(const Config& root, const std::string& base_dir) {
  try {
    return ScenarioReader(root, base_dir).Read();
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {
    throw ConfigError(root.Source() + ": not a valid scenario: " + e.what());
  }
}

}  // namespace

Scenario LoadScenarioFromString(const std::string& yaml_text, const std::string& source,
                                const std::string& base_dir) {
  return ReadGuarded(Config::FromString(yaml_text, source), base_dir);
}

Scenario LoadScenario(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw ConfigError(path + ": cannot open file");
  const Config root = Config::LoadFile(path);
  std::string base_dir = std::filesystem::path(path).parent_path().string();
  if (base_dir.empty()) base_dir = ".";
  Scenario scenario = ReadGuarded(root, base_dir);
  if (scenario.name.empty()) scenario.name = std::filesystem::path(path).stem().string();
  return scenario;
}

std::vector<RecordedTrack> ReadRecordedTracks(const std::string& path) {
  std::error_code ec;
  std::ifstream in(path);
  if (!in || !std::filesystem::is_regular_file(path, ec)) {
    throw ConfigError(path + ": cannot open file");
  }
  std::map<int64_t, RecordedTrack> by_id;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& message) {
    throw ConfigError(path + ":" + std::to_string(line_number) + ": " + message);
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_number == 1) {
      if (line != "t_s\tid\tx_m\ty_m") fail("expected the header \"t_s<TAB>id<TAB>x_m<TAB>y_m\"");
      continue;
    }
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    std::string field;
    while (std::getline(row, field, '\t')) fields.push_back(field);
    std::optional<double> t_s, x_m, y_m;
    std::optional<int64_t> whole_id;
    if (fields.size() == 4) {
      t_s = ParseFiniteDouble(fields[0]);
      whole_id = ParseWholeNumber(fields[1]);
      x_m = ParseFiniteDouble(fields[2]);
      y_m = ParseFiniteDouble(fields[3]);
    }
    if (!t_s || !whole_id || !x_m || !y_m) {
      fail("expected four tab-separated numbers t_s, id, x_m, y_m");
      continue;  // (fail throws)
    }
    const TimedPoint point{*t_s, *x_m, *y_m};
    const int64_t id = *whole_id;
    if (std::abs(id) > kMaxRecordedId) fail("person id must be within +-1e15");
    RecordedTrack& track = by_id[id];
    track.id = id;
    if (!track.points.empty() && !(point.t_s > track.points.back().t_s)) {
      std::ostringstream message;
      message << "person " << id << ": time " << point.t_s << " does not increase (previous "
              << track.points.back().t_s << ")";
      fail(message.str());
    }
    track.points.push_back(point);
  }
  if (line_number == 0) throw ConfigError(path + ": empty file");
  std::vector<RecordedTrack> tracks;
  for (auto& entry : by_id) tracks.push_back(std::move(entry.second));
  return tracks;
}

std::string ResolveScenarioPath(const std::string& name_or_path,
                                const std::vector<std::string>& search_roots) {
  namespace fs = std::filesystem;
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       fs::path(name_or_path).extension() == ".yaml" ||
                       fs::path(name_or_path).extension() == ".yml";
  if (is_path) {
    if (!fs::is_regular_file(name_or_path)) throw ConfigError(name_or_path + ": cannot open file");
    return name_or_path;
  }
  std::string tried;
  std::string available;
  for (const std::string& root : search_roots) {
    const fs::path dir = fs::path(root) / "config" / "scenarios";
    const fs::path candidate = dir / (name_or_path + ".yaml");
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
    tried += (tried.empty() ? "" : ", ") + candidate.string();
    if (available.empty() && fs::is_directory(dir, ec)) {
      std::vector<std::string> names;
      for (const auto& entry : fs::directory_iterator(dir, ec)) {
        if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
      }
      std::sort(names.begin(), names.end());
      for (const std::string& n : names) available += (available.empty() ? "" : ", ") + n;
    }
  }
  throw ConfigError("scenario \"" + name_or_path + "\" not found (tried " + tried + ")" +
                    (available.empty() ? "" : "; shipped scenarios: " + available));
}

std::vector<std::string> ScenarioSearchRoots(const std::string& source_dir) {
  std::vector<std::filesystem::path> candidates = {source_dir};
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back(exe.parent_path() / ".." / "..");
    candidates.push_back(exe.parent_path() / "..");
  }
  std::vector<std::string> roots;
  for (const std::filesystem::path& candidate : candidates) {
    const std::string root = candidate.lexically_normal().string();
    const std::string trimmed =
        root.size() > 1 && root.back() == '/' ? root.substr(0, root.size() - 1) : root;
    if (std::find(roots.begin(), roots.end(), trimmed) == roots.end()) roots.push_back(trimmed);
  }
  return roots;
}

}  // namespace slammtt
