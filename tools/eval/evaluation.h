// The evaluation of one run against ground truth (pure: EvalInput in, EvaluationReport out).
// Every definition is written out in docs/evaluation.md; in short:
//
// - Frames: the estimator's map frame and the base's odometry frame are each anchored to the
//   truth at the first ground-truth scan where they exist, by a rigid transform (no fitting),
//   applied to poses, landmarks and tracks (trajectory_error.h, pose2.h).
// - Robot: absolute trajectory error of POSE at every ground-truth scan with a POSE of the same
//   utime; of ODOMETRY interpolated at the ground-truth times (dead reckoning, for comparison).
// - Map: the final MAP against the static objects that were ever visible (map_score.h).
// - Tracking, per ground-truth scan from the first to the last TRACKS message (a scan in that
//   window without TRACKS counts as an empty output): truth = visible MOVING objects, output =
//   confirmed tracks labelled MOVING; an unmatched track within the threshold of an existing
//   but invisible mover is "don't care" and is left out of CLEAR-MOT and of OSPA/GOSPA.
// - Classification: visible objects of both classes against every confirmed track
//   (classification_score.h), over the same window.
// Missing inputs leave the affected results empty, with a one-line note each.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/eval/eval_input.h"
#include "tools/metrics/classification_score.h"
#include "tools/metrics/clear_mot.h"
#include "tools/metrics/map_score.h"
#include "tools/metrics/trajectory_error.h"

namespace slammtt {

struct EvalOptions {
  double match_threshold_m = 1.0;  // CLEAR-MOT, map and classification matches
  double ospa_cutoff_m = 1.0;      // c of OSPA and GOSPA
  double ospa_order = 2.0;         // p of OSPA and GOSPA
  double gospa_alpha = 2.0;
};

struct TrajectoryResult {
  Pose2 anchor;              // estimate frame -> truth frame
  int64_t anchor_utime = 0;
  TrajectoryError error;
  std::vector<TimedPose> anchored;  // the estimate in the truth frame, at the scored times
};

struct TrackingScan {
  int64_t utime = 0;
  int num_truth = 0;
  int num_tracks = 0;  // confirmed MOVING tracks, don't-cares included
  int num_matches = 0;
  int num_dont_care = 0;
  double ospa_m = 0.0;
  double gospa_m = 0.0;
  bool had_tracks_message = true;
};

struct TrackingResult {
  std::vector<TrackingScan> scans;
  ClearMotSummary clear_mot;
  double ospa_mean_m = 0.0;
  double ospa_max_m = 0.0;
  double ospa_localisation_mean_m = 0.0;
  double ospa_cardinality_mean_m = 0.0;
  double gospa_mean_m = 0.0;
  double gospa_max_m = 0.0;
  int64_t gospa_missed = 0;
  int64_t gospa_false = 0;
  int64_t scans_without_tracks = 0;
};

// A track's path in the truth frame (confirmed MOVING samples), for pictures.
struct TrackPath {
  int64_t id = 0;
  std::vector<Eigen::Vector2d> points;
};

struct AnchoredLandmark {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  enum class Kind { kStatic, kMover, kUnexplained } kind = Kind::kUnexplained;
};

struct EvaluationReport {
  EvalOptions options;
  std::string source;
  int64_t truth_scans = 0;
  int64_t first_utime = 0;
  int64_t last_utime = 0;
  std::optional<TrajectoryResult> robot;     // POSE
  std::optional<TrajectoryResult> odometry;  // ODOMETRY
  std::optional<MapScore> map;
  std::optional<TrackingResult> tracking;
  std::optional<ClassificationSummary> classification;
  std::vector<std::string> notes;

  // For pictures, in the truth frame.
  std::vector<TimedPose> truth_trajectory;
  std::vector<std::vector<Eigen::Vector2d>> mover_paths;  // per moving object, all scans
  std::vector<IdentifiedPoint> static_objects;            // ever visible
  std::vector<IdentifiedPoint> unseen_static_objects;     // never visible
  std::vector<AnchoredLandmark> landmarks;                // final map
  std::vector<TrackPath> track_paths;
};

// Scores `input`. Throws std::invalid_argument for options out of range (thresholds not
// positive, order < 1, alpha outside (0, 2]).
EvaluationReport Evaluate(const EvalInput& input, const EvalOptions& options);

}  // namespace slammtt
