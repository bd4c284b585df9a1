#include "tools/eval/eval_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <stdexcept>
#include <system_error>

#include "runtime/command_line_options.h"
#include "runtime/config_options.h"
#include "runtime/lcm_io.h"
#include "runtime/output_file.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"
#include "slammtt_msgs/trajectory_t.hpp"

namespace slammtt {
namespace {

// Positions, velocities and covariances beyond these are not a robot's world but a broken
// message; bounding them also keeps every later sum and difference finite.
constexpr double kMaxMagnitude = 1e6;
// Times from 0 to about year 33000 in microseconds: differences of two never overflow.
constexpr int64_t kMaxUtime = 1000000000000000000LL;

bool Finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v) || std::abs(v) > kMaxMagnitude) return false;
  }
  return true;
}

template <class T>
bool AllFinite(const T* values, int count) {
  for (int k = 0; k < count; ++k) {
    if (!std::isfinite(values[k]) || std::abs(values[k]) > kMaxMagnitude) return false;
  }
  return true;
}

bool ValidUtime(int64_t utime) { return utime >= 0 && utime <= kMaxUtime; }

// Sorts by utime (stable: a repeated utime keeps the first message) and drops repeats.
template <class T>
int64_t SortUnique(std::vector<T>* items) {
  std::stable_sort(items->begin(), items->end(),
                   [](const T& a, const T& b) { return a.utime < b.utime; });
  const auto end = std::unique(items->begin(), items->end(),
                               [](const T& a, const T& b) { return a.utime == b.utime; });
  const int64_t dropped = static_cast<int64_t>(items->end() - end);
  items->erase(end, items->end());
  return dropped;
}

using Truth = slammtt_msgs::object_truth_t;

bool KnownKind(int8_t kind) { return kind >= 0 && kind <= Truth::KIND_LEG; }

TruthKind ToTruthKind(int8_t kind) {
  switch (kind) {
    case Truth::KIND_WALL: return TruthKind::kWall;
    case Truth::KIND_FURNITURE: return TruthKind::kFurniture;
    case Truth::KIND_POST: return TruthKind::kPost;
    case Truth::KIND_DISC: return TruthKind::kDisc;
    case Truth::KIND_PERSON: return TruthKind::kPerson;
    default: return TruthKind::kUnspecified;
  }
}

// One GROUND_TRUTH message as a TruthScan (eval_log.h). False when anything in it is unusable:
// a non-finite or absurd number, an unknown class or kind, a negative beam count, a repeated id,
// a leg whose person is not in the message, a wall or furniture kind on a compact object.
bool ReadTruthScan(const slammtt_msgs::ground_truth_t& msg, TruthScan* scan,
                   std::vector<TruthSegment>* segments) {
  bool ok = ValidUtime(msg.utime) && Finite({msg.robot_x_m, msg.robot_y_m, msg.robot_heading_rad});
  scan->utime = msg.utime;
  scan->robot = Pose2{msg.robot_x_m, msg.robot_y_m, WrapAngle(msg.robot_heading_rad)};
  std::map<int64_t, int> leg_beams;  // person id -> beams on its better-seen leg
  std::set<int64_t> ids;
  for (const auto& o : msg.objects) {
    ok = ok && Finite({o.x_m, o.y_m, o.vx_mps, o.vy_mps, o.radius_m}) &&
         (o.object_class == Truth::CLASS_STATIC || o.object_class == Truth::CLASS_MOVING) &&
         o.beams_on_object >= 0 && KnownKind(o.kind) && o.kind != Truth::KIND_WALL &&
         ids.insert(o.id).second;
    if (o.kind == Truth::KIND_LEG) {
      int& beams = leg_beams[o.parent_id];
      beams = std::max(beams, o.beams_on_object);
      scan->legs.push_back(TruthLeg{o.parent_id, Eigen::Vector2d(o.x_m, o.y_m), o.radius_m});
      continue;
    }
    scan->objects.push_back(TruthObjectSample{
        o.id, Eigen::Vector2d(o.x_m, o.y_m), Eigen::Vector2d(o.vx_mps, o.vy_mps),
        o.object_class == Truth::CLASS_MOVING, o.visible != 0, o.beams_on_object,
        ToTruthKind(o.kind)});
  }
  for (TruthObjectSample& o : scan->objects) {
    if (o.kind != TruthKind::kPerson) continue;
    const auto legs = leg_beams.find(o.id);
    o.beams_on_object = legs != leg_beams.end() ? legs->second : 0;
    if (legs != leg_beams.end()) leg_beams.erase(legs);
  }
  ok = ok && leg_beams.empty();  // every leg belongs to a person of this message
  for (const auto& g : msg.segments) {
    ok = ok && Finite({g.x0_m, g.y0_m, g.x1_m, g.y1_m}) && g.beams_on_segment >= 0 &&
         (g.kind == slammtt_msgs::segment_truth_t::KIND_WALL ||
          g.kind == slammtt_msgs::segment_truth_t::KIND_FURNITURE);
    segments->push_back(TruthSegment{g.id, ToTruthKind(g.kind), Eigen::Vector2d(g.x0_m, g.y0_m),
                                     Eigen::Vector2d(g.x1_m, g.y1_m)});
  }
  return ok;
}

Eigen::Vector2d Polar(double range_m, double bearing_rad) {
  return range_m * Eigen::Vector2d(std::cos(bearing_rad), std::sin(bearing_rad));
}

// The valid, finite beams of a scan as points in the sensor frame.
std::vector<Eigen::Vector2d> BeamPoints(const slammtt_msgs::laser_scan_t& scan) {
  std::vector<Eigen::Vector2d> points;
  for (size_t k = 0; k < scan.angle_rad.size(); ++k) {
    const double range = scan.range_m[k];
    if (scan.valid[k] == 0 || !std::isfinite(range) || !std::isfinite(scan.angle_rad[k]) ||
        range <= 0.0 || range > kMaxMagnitude) {
      continue;
    }
    points.push_back(Polar(range, scan.angle_rad[k]));
  }
  return points;
}

// FEATURES as a snapshot; nullopt when a number is not finite or a leg index is out of range.
std::optional<ScanSnapshot> SnapshotFromFeatures(const slammtt_msgs::features_t& msg) {
  ScanSnapshot snapshot;
  snapshot.utime = msg.utime;
  for (const auto& f : msg.features) {
    if (!Finite({f.range_m, f.bearing_rad, f.width_m, f.leg_likeness})) return std::nullopt;
    snapshot.points.push_back({Polar(f.range_m, f.bearing_rad), f.width_m, f.leg_likeness});
  }
  for (const auto& l : msg.lines) {
    if (!Finite({l.first_x_m, l.first_y_m, l.last_x_m, l.last_y_m})) return std::nullopt;
    snapshot.lines.push_back({Eigen::Vector2d(l.first_x_m, l.first_y_m),
                              Eigen::Vector2d(l.last_x_m, l.last_y_m)});
  }
  for (const auto& p : msg.people) {
    if (!Finite({p.range_m, p.bearing_rad})) return std::nullopt;
    ScanSnapshot::Person person;
    person.position_m = Polar(p.range_m, p.bearing_rad);
    for (int k = 0; k < 2 && k < p.num_legs; ++k) {
      if (p.leg_index[k] < 0 || p.leg_index[k] >= msg.num_features) return std::nullopt;
      person.legs.push_back(p.leg_index[k]);
    }
    snapshot.people.push_back(std::move(person));
  }
  return snapshot;
}

// A pose_t into `poses`, or counted as rejected under `key` (undecodable, a bad utime, not
// finite). The key is counted (accepted) from its first message on.
void ReadPose(const LogEventView& e, const std::string& key, EvalInput* input,
              std::vector<TimedPose>* poses) {
  input->accepted[key] += 0;
  slammtt_msgs::pose_t msg{};
  if (!Decode(e.data, e.size, &msg) || !ValidUtime(msg.utime) ||
      !Finite({msg.x_m, msg.y_m, msg.heading_rad})) {
    ++input->rejected[key];
    return;
  }
  input->rejected[key] += 0;
  poses->push_back({msg.utime, Pose2{msg.x_m, msg.y_m, WrapAngle(msg.heading_rad)}});
}

// A map_t's landmarks and lines; false when it is undecodable, has a bad utime or a number
// that is not finite.
bool ReadMap(const LogEventView& e, std::vector<LandmarkSample>* landmarks,
             std::vector<LineLandmarkSample>* lines, int64_t* utime) {
  slammtt_msgs::map_t msg{};
  if (!Decode(e.data, e.size, &msg)) return false;
  bool ok = ValidUtime(msg.utime);
  *utime = msg.utime;
  for (const auto& l : msg.landmarks) {
    ok = ok && Finite({l.x_m, l.y_m}) && AllFinite(l.covariance, 4);
    LandmarkSample sample;
    sample.id = l.id;
    sample.position_m = Eigen::Vector2d(l.x_m, l.y_m);
    sample.covariance << l.covariance[0], l.covariance[1], l.covariance[2], l.covariance[3];
    landmarks->push_back(sample);
  }
  for (const auto& l : msg.lines) {
    ok = ok && Finite({l.rho_m, l.alpha_rad, l.from_x_m, l.from_y_m, l.to_x_m, l.to_y_m});
    LineLandmarkSample sample;
    sample.id = l.id;
    sample.line = Eigen::Vector2d(l.rho_m, l.alpha_rad);
    sample.from_m = Eigen::Vector2d(l.from_x_m, l.from_y_m);
    sample.to_m = Eigen::Vector2d(l.to_x_m, l.to_y_m);
    lines->push_back(sample);
  }
  return ok;
}

// A SMOOTHED_TRAJECTORY's keyframes; false (nothing kept) when a utime is invalid or not
// increasing, or a number is not finite.
bool ReadTrajectory(const LogEventView& e, std::vector<TimedPose>* poses, int64_t* utime) {
  slammtt_msgs::trajectory_t msg{};
  if (!Decode(e.data, e.size, &msg) || !ValidUtime(msg.utime)) return false;
  poses->clear();
  for (int i = 0; i < msg.num_poses; ++i) {
    if (!ValidUtime(msg.pose_utime[i]) ||
        (!poses->empty() && msg.pose_utime[i] <= poses->back().utime) ||
        !Finite({msg.x_m[i], msg.y_m[i], msg.heading_rad[i]})) {
      return false;
    }
    poses->push_back({msg.pose_utime[i], Pose2{msg.x_m[i], msg.y_m[i],
                                               WrapAngle(msg.heading_rad[i])}});
  }
  *utime = msg.utime;
  return true;
}

}  // namespace

EvalInput ReadEvalInput(const std::string& path, const Channels& channels, LogReadResult* read) {
  EvalInput input;
  input.source = path;
  const std::string truth_channel = channels.Get("ground_truth");
  const std::string odometry_channel = channels.Get("odometry");
  const std::string pose_channel = channels.Get("pose");
  const std::string tracks_channel = channels.Get("tracks");
  const std::string map_channel = channels.Get("map");
  const std::string laser_scan_channel = channels.Get("laser_scan");
  const std::string features_channel = channels.Get("features");
  const std::string smoothed_pose_channel = channels.Get("smoothed_pose");
  const std::string smoothed_map_channel = channels.Get("smoothed_map");
  const std::string smoothed_trajectory_channel = channels.Get("smoothed_trajectory");
  const std::string laser_geometry_channel = channels.Get("laser_geometry");
  int64_t last_scan_utime = -1;  // the last decodable LASER_SCAN, kept for the snapshot
  std::vector<Eigen::Vector2d> last_scan_beams;
  for (const char* key : {"ground_truth", "odometry", "pose", "tracks", "map"}) {
    input.rejected[key] = 0;
    input.accepted[key] = 0;
  }

  *read = ForEachLogEvent(path, [&](const LogEventView& e) {
    if (e.channel == truth_channel) {
      slammtt_msgs::ground_truth_t msg{};
      if (!Decode(e.data, e.size, &msg)) {
        ++input.rejected["ground_truth"];
        return;
      }
      TruthScan scan;
      std::vector<TruthSegment> segments;
      if (!ReadTruthScan(msg, &scan, &segments)) {
        ++input.rejected["ground_truth"];
        return;
      }
      if (input.static_segments.empty()) input.static_segments = std::move(segments);
      input.truth.push_back(std::move(scan));
    } else if (e.channel == laser_scan_channel) {
      ++input.laser_scans;
      slammtt_msgs::laser_scan_t msg{};
      if (Decode(e.data, e.size, &msg)) {
        last_scan_utime = msg.utime;
        last_scan_beams = BeamPoints(msg);
      }
    } else if (e.channel == laser_geometry_channel) {
      slammtt_msgs::laser_geometry_t msg{};
      if (input.laser_mount || !Decode(e.data, e.size, &msg)) return;
      const Pose2 mount{msg.mount_forward_m, msg.mount_left_m, msg.mount_yaw_rad};
      if (std::isfinite(mount.x_m) && std::isfinite(mount.y_m) &&
          std::isfinite(mount.heading_rad) && std::abs(mount.x_m) <= 100.0 &&
          std::abs(mount.y_m) <= 100.0) {
        input.laser_mount = mount;
      }
    } else if (e.channel == features_channel) {
      slammtt_msgs::features_t msg{};
      if (!Decode(e.data, e.size, &msg) || msg.utime != last_scan_utime) return;
      const size_t best = input.snapshot ? input.snapshot->people.size() : 0;
      if (input.snapshot && msg.people.size() <= best) return;
      if (std::optional<ScanSnapshot> snapshot = SnapshotFromFeatures(msg)) {
        snapshot->beams_m = last_scan_beams;
        input.snapshot = std::move(snapshot);
      }
    } else if (e.channel == odometry_channel) {
      slammtt_msgs::odometry_t msg{};
      if (!Decode(e.data, e.size, &msg) || !ValidUtime(msg.utime) ||
          !Finite({msg.x_m, msg.y_m, msg.heading_rad})) {
        ++input.rejected["odometry"];
        return;
      }
      input.odometry.push_back({msg.utime, Pose2{msg.x_m, msg.y_m, WrapAngle(msg.heading_rad)}});
    } else if (e.channel == pose_channel) {
      ReadPose(e, "pose", &input, &input.estimate);
    } else if (e.channel == smoothed_pose_channel) {
      ReadPose(e, "smoothed_pose", &input, &input.smoothed_estimate);
    } else if (e.channel == smoothed_map_channel) {
      input.accepted["smoothed_map"] += 0;
      input.rejected["smoothed_map"] += 0;
      std::vector<LandmarkSample> landmarks;
      std::vector<LineLandmarkSample> lines;
      int64_t utime = 0;
      if (!ReadMap(e, &landmarks, &lines, &utime) ||
          (input.final_smoothed_map && utime < input.final_smoothed_map_utime)) {
        ++input.rejected["smoothed_map"];
        return;
      }
      ++input.accepted["smoothed_map"];
      input.final_smoothed_map = std::move(landmarks);
      input.final_smoothed_map_utime = utime;
    } else if (e.channel == smoothed_trajectory_channel) {
      input.accepted["smoothed_trajectory"] += 0;
      input.rejected["smoothed_trajectory"] += 0;
      std::vector<TimedPose> poses;
      int64_t utime = 0;
      // Not newer than the last accepted one: rejected (the first of a utime wins, as in
      // slammtt-export).
      if (!ReadTrajectory(e, &poses, &utime) ||
          (input.final_smoothed_trajectory && utime <= input.final_smoothed_trajectory_utime)) {
        ++input.rejected["smoothed_trajectory"];
        return;
      }
      ++input.accepted["smoothed_trajectory"];
      input.final_smoothed_trajectory = std::move(poses);
      input.final_smoothed_trajectory_utime = utime;
    } else if (e.channel == tracks_channel) {
      slammtt_msgs::tracks_t msg{};
      if (!Decode(e.data, e.size, &msg)) {
        ++input.rejected["tracks"];
        return;
      }
      bool ok = ValidUtime(msg.utime);
      TrackScan scan;
      scan.utime = msg.utime;
      for (const auto& t : msg.tracks) {
        ok = ok && Finite({t.x_m, t.y_m, t.vx_mps, t.vy_mps}) && AllFinite(t.covariance, 16) &&
             t.object_class >= 0 && t.object_class <= 2 && std::isfinite(t.coasting_s) &&
             t.coasting_s >= 0.0 &&
             (t.kind == slammtt_msgs::track_t::KIND_OTHER ||
              t.kind == slammtt_msgs::track_t::KIND_PERSON);
        TrackSample sample;
        sample.id = t.id;
        sample.position_m = Eigen::Vector2d(t.x_m, t.y_m);
        sample.label = static_cast<ObjectLabel>(t.object_class);
        sample.confirmed = t.confirmed != 0;
        sample.reported = t.reported != 0;
        sample.measured = t.measured != 0;
        sample.coasting_s = t.coasting_s;
        sample.person = t.kind == slammtt_msgs::track_t::KIND_PERSON;
        scan.tracks.push_back(sample);
      }
      for (size_t a = 0; ok && a < scan.tracks.size(); ++a) {
        for (size_t b = a + 1; b < scan.tracks.size(); ++b) {
          ok = ok && scan.tracks[a].id != scan.tracks[b].id;
        }
      }
      if (!ok) {
        ++input.rejected["tracks"];
        return;
      }
      input.tracks.push_back(std::move(scan));
    } else if (e.channel == map_channel) {
      std::vector<LandmarkSample> landmarks;
      std::vector<LineLandmarkSample> lines;
      int64_t utime = 0;
      if (!ReadMap(e, &landmarks, &lines, &utime) ||
          (input.final_map && utime < input.final_map_utime)) {
        ++input.rejected["map"];
        return;
      }
      ++input.accepted["map"];
      input.final_map = std::move(landmarks);
      input.final_map_lines = std::move(lines);
      input.final_map_utime = utime;
    }
  });
  input.rejected["ground_truth"] += SortUnique(&input.truth);
  input.rejected["odometry"] += SortUnique(&input.odometry);
  input.rejected["pose"] += SortUnique(&input.estimate);
  input.rejected["tracks"] += SortUnique(&input.tracks);
  if (input.accepted.count("smoothed_pose") != 0 || input.rejected.count("smoothed_pose") != 0) {
    input.rejected["smoothed_pose"] += SortUnique(&input.smoothed_estimate);
    input.accepted["smoothed_pose"] = static_cast<int64_t>(input.smoothed_estimate.size());
  }
  input.accepted["ground_truth"] = static_cast<int64_t>(input.truth.size());
  input.accepted["odometry"] = static_cast<int64_t>(input.odometry.size());
  input.accepted["pose"] = static_cast<int64_t>(input.estimate.size());
  input.accepted["tracks"] = static_cast<int64_t>(input.tracks.size());
  return input;
}

EvalOptions ReadEvalOptions(const Config& section) {
  EvalOptions options;
  ConfigOptionReader reader(section);
  VisitEvalOptions(&reader, &options);
  section.CheckUnused();
  return options;
}

EvalOptions ReadStackEvalOptions(const Config& stack) {
  const Config eval = stack.Child("eval");
  const bool eval_sets_min_beams = eval.Has("min_beams");
  EvalOptions options = ReadEvalOptions(eval);
  const Config estimator = stack.Child("estimator");
  options.sensor_mount_given = estimator.Has("sensor_forward_m") || estimator.Has("sensor_left_m");
  options.sensor_forward_m = estimator.GetDouble("sensor_forward_m", options.sensor_forward_m);
  options.sensor_left_m = estimator.GetDouble("sensor_left_m", options.sensor_left_m);
  if (!std::isfinite(options.sensor_forward_m) || !std::isfinite(options.sensor_left_m) ||
      std::abs(options.sensor_forward_m) > 100.0 || std::abs(options.sensor_left_m) > 100.0) {
    estimator.FailKey("sensor_forward_m", "the mount must be within 100 m of the axle");
  }
  const Config segmenter = stack.Child("segmenter");
  if (!eval_sets_min_beams && segmenter.Has("min_points")) {
    const int64_t min_points = segmenter.GetInt("min_points", options.min_beams);
    if (min_points < 1 || min_points > kMaxMinBeams) {
      segmenter.FailKey("min_points", "must be in [1, " + std::to_string(kMaxMinBeams) +
                                          "] (eval.min_beams follows it)");
    }
    options.min_beams = static_cast<int>(min_points);
  }
  return options;
}

namespace {

// The keys of the `eval:` section the command line may set (runtime/command_line_options.h).
const CommandLineOptions& EvalCommandLineOptions() {
  static const CommandLineOptions options(
      {"min_beams", "min_moving_speed_mps", "match_threshold_m"}, "eval");
  return options;
}

}  // namespace

void AddEvalCommandLineOptions(CommandLine* command_line) {
  EvalCommandLineOptions().Declare(command_line, VisitEvalOptions);
  command_line->AddFlag("options-table",
                        "print the table of every key of the eval: section (Markdown, "
                        "docs/evaluation.md) and exit");
}

void ApplyEvalCommandLine(const CommandLine& command_line, EvalOptions* options) {
  EvalCommandLineOptions().Apply(command_line, VisitEvalOptions, options);
}

void WriteFileAtomically(const std::string& path, const std::string& text) {
  OutputFile file(path);
  if (std::fwrite(text.data(), 1, text.size(), file.stream()) != text.size()) {
    throw std::runtime_error(path + ": write failed");
  }
  file.Commit();
}

std::vector<std::string> WriteTextFiles(
    const std::string& directory, const std::vector<std::pair<std::string, std::string>>& files) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw std::runtime_error(directory + ": cannot create directory: " + error.message());
  std::vector<std::string> written;
  for (const auto& [name, text] : files) {
    written.push_back(directory + "/" + name);
    WriteFileAtomically(written.back(), text);
  }
  return written;
}

}  // namespace slammtt
