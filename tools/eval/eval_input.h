// What slammtt-eval takes from a log, as plain data (no LCM): ground truth, odometry and the
// estimator's outputs, each in its own frame, plus the count of messages it had to reject.
// Filled by ReadEvalInput (eval_log.h); scored by Evaluate (evaluation.h).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/metrics/classification_score.h"
#include "tools/metrics/pose2.h"

namespace slammtt {

// What a ground-truth object is (object_truth_t / segment_truth_t KIND_*). kUnspecified: a log
// that does not say (kind 0); such objects are scored by their class alone.
enum class TruthKind { kUnspecified, kWall, kFurniture, kPost, kDisc, kPerson };

// A compact object or a person. The legs of a person are not objects of their own: they are
// folded into their person (eval_log.h), whose beams_on_object is then the beams on its
// better-seen leg, so that "visible" means what the segmenter needs: a cluster of min_beams
// points on one leg.
struct TruthObjectSample {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // world frame
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();  // world frame, at this moment
  bool moving = false;   // CLASS_MOVING (it may stand still for a while)
  // GROUND_TRUTH's `visible`: the world emitted a point feature of it (FEATURES output), or at
  // least one beam hit it first (LASER_SCAN output: beams_on_object >= 1). The evaluation's own
  // rule for a log with LASER_SCAN is beams_on_object >= EvalOptions::min_beams (evaluation.h).
  bool visible = false;
  int beams_on_object = 0;  // laser beams whose first hit is this object (>= 0)
  TruthKind kind = TruthKind::kUnspecified;
};

// A straight static surface of the world (a wall, a furniture side), world frame.
struct TruthSegment {
  int64_t id = 0;
  TruthKind kind = TruthKind::kWall;
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
};

// One leg of a person (for pictures; the scores use the person, TruthObjectSample).
struct TruthLeg {
  int64_t person_id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
};

// GROUND_TRUTH at one scan time.
struct TruthScan {
  int64_t utime = 0;
  Pose2 robot;
  std::vector<TruthObjectSample> objects;
  std::vector<TruthLeg> legs;
};

// What perception made of one scan, in the sensor frame (x forward, y left), for the picture of
// a scan: the valid beams of LASER_SCAN and the features of FEATURES with the same utime.
struct ScanSnapshot {
  struct Point {
    Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
    double width_m = 0.0;
    double leg_likeness = 0.0;
  };
  struct Line {
    Eigen::Vector2d first_m = Eigen::Vector2d::Zero();
    Eigen::Vector2d last_m = Eigen::Vector2d::Zero();
  };
  struct Person {
    Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
    std::vector<int> legs;  // indices into points
  };
  int64_t utime = 0;
  std::vector<Eigen::Vector2d> beams_m;
  std::vector<Point> points;
  std::vector<Line> lines;
  std::vector<Person> people;
};

// One object of TRACKS, in the estimator's map frame.
struct TrackSample {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  ObjectLabel label = ObjectLabel::kUndecided;
  bool confirmed = false;
  // track_t's honest reporting: confirmed and measured recently enough to be shown (the
  // estimator's tracks_report_measured_within_s), measured in this scan, time since measured.
  bool reported = false;
  bool measured = false;
  double coasting_s = 0.0;
  bool person = false;  // kind PERSON
};

struct TrackScan {
  int64_t utime = 0;
  std::vector<TrackSample> tracks;
};

// A landmark of MAP, in the estimator's map frame.
struct LandmarkSample {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

// A line landmark of MAP (a wall or furniture side), in the estimator's map frame.
struct LineLandmarkSample {
  int64_t id = 0;
  Eigen::Vector2d line = Eigen::Vector2d::Zero();  // (rho_m, alpha_rad)
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();  // observed extent's end points
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
};

struct EvalInput {
  std::string source;                 // the log's path, for reports
  std::vector<TruthScan> truth;       // sorted by utime, unique utimes
  // The world's straight static surfaces, from the first accepted GROUND_TRUTH that has any
  // (they do not move). Not part of the point map's truth: for pictures and line scoring.
  std::vector<TruthSegment> static_segments;
  std::vector<TimedPose> odometry;    // odometry frame, sorted, unique
  std::vector<TimedPose> estimate;    // POSE, map frame, sorted, unique
  std::vector<TrackScan> tracks;      // sorted, unique
  // The smoother's outputs (slammtt-smoother), in the estimator's map frame: SMOOTHED_POSE
  // (sorted, unique), the last SMOOTHED_MAP and the last SMOOTHED_TRAJECTORY (its keyframes,
  // sorted, unique: the trajectory as the smoother estimated it at the end).
  std::vector<TimedPose> smoothed_estimate;
  std::optional<std::vector<LandmarkSample>> final_smoothed_map;
  int64_t final_smoothed_map_utime = 0;
  std::optional<std::vector<TimedPose>> final_smoothed_trajectory;
  int64_t final_smoothed_trajectory_utime = 0;
  std::optional<std::vector<LandmarkSample>> final_map;  // the last MAP message
  std::vector<LineLandmarkSample> final_map_lines;       // its lines
  int64_t final_map_utime = 0;
  // LASER_SCAN messages in the log (counted, not decoded): a log with raw scans, whose features
  // come from the segmenter, so visibility is judged by beams_on_object (evaluation.h).
  int64_t laser_scans = 0;
  // The scan with the most person features (the earliest of those), with its beams: the picture
  // of what perception sees. Absent without a LASER_SCAN and FEATURES pair of the same utime.
  std::optional<ScanSnapshot> snapshot;
  // The laser's mount (forward, left, yaw) of the log's first usable LASER_GEOMETRY: the scan
  // picture's mount when the configuration gives none (EvalOptions::sensor_mount_given).
  std::optional<Pose2> laser_mount;
  // Messages per channel key ("ground_truth", "odometry", "pose", "tracks", "map"; and
  // "smoothed_pose", "smoothed_map" when the log has any) that were undecodable, carried NaN/inf
  // or an unknown class, or repeated an earlier utime.
  std::map<std::string, int64_t> rejected;
  std::map<std::string, int64_t> accepted;
};

}  // namespace slammtt
