// The evaluation of one run against ground truth (pure: EvalInput in, EvaluationReport out).
// Every definition is written out in docs/evaluation.md; in short:
//
// - Frames: the estimator's map frame and the base's odometry frame are each anchored to the
//   truth at the first ground-truth scan where they exist, by a rigid transform (no fitting),
//   applied to poses, landmarks and tracks (trajectory_error.h, pose2.h).
// - Robot: absolute trajectory error of POSE at every ground-truth scan with a POSE of the same
//   utime; of ODOMETRY interpolated at the ground-truth times (dead reckoning, for comparison).
// - Map: the final MAP against the static objects that were ever visible (map_score.h).
// - Smoother (issue 14): SMOOTHED_POSE and the final SMOOTHED_MAP, when present, scored by the
//   same rules, each anchored at the first ground-truth scan with a SMOOTHED_POSE.
// - Visibility: in a log with LASER_SCAN (raw scans, features made by the segmenter) an object
//   is visible at a scan when beams_on_object >= min_beams (the segmenter's minimum cluster
//   size: fewer points never make a feature); in a feature log, the world's `visible` flag (a
//   feature of it was emitted). Used by the map, tracking and classification alike.
// - Standing still: a MOVING object whose true speed is below min_moving_speed_mps at a scan is,
//   while it stands, indistinguishable from a post, and the paper's method turns it into a static
//   object (Algorithm 2, line 12, "determine state of objects": stationary objects become moving
//   and vice versa): "don't care" for tracking at that scan, not judged by the classification.
// - Tracking, per ground-truth scan from the first to the last TRACKS message (a scan in that
//   window without TRACKS counts as an empty output): truth = visible MOVING objects that are not
//   standing, output = reported tracks (track_t.reported: confirmed and measured recently)
//   labelled MOVING; the same with every confirmed track, coasting ones included
//   (tracking_with_coasting). Don't care (clear_mot.h, DontCare): a
//   track the optimal assignment gives to a visible standing mover, and an unmatched track
//   within the threshold of an existing but invisible mover; both are left out of CLEAR-MOT and
//   of OSPA/GOSPA. Every identity switch and fragmentation is listed with its time.
// - People (people_tracking): truth = visible people (TruthKind::kPerson; every mover in a log
//   that names no person), standing ones counted as people (no standing rule); output =
//   reported tracks labelled MOVING or of kind PERSON (a standing person is a STATIC track of
//   kind PERSON). Invisible people are don't-cares as above.
// - Classification: visible objects of both classes against every confirmed track
//   (classification_score.h), over the same window; standing scans of movers are not judged.
// Missing inputs leave the affected results empty, with a one-line note each. Without
// GROUND_TRUTH nothing is scored, but what the log holds is still prepared for the pictures
// (EvaluationReport::log_only).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/options_schema.h"
#include "tools/eval/eval_input.h"
#include "tools/metrics/classification_score.h"
#include "tools/metrics/clear_mot.h"
#include "tools/metrics/identity_metrics.h"
#include "tools/metrics/line_map_score.h"
#include "tools/metrics/map_score.h"
#include "tools/metrics/trajectory_error.h"

namespace slammtt {

struct EvalOptions {
  double match_threshold_m = 1.0;  // CLEAR-MOT, map and classification matches
  double ospa_cutoff_m = 1.0;      // c of OSPA and GOSPA
  double ospa_order = 2.0;         // p of OSPA and GOSPA
  double gospa_alpha = 2.0;
  // Visibility in a log with LASER_SCAN: beams_on_object >= min_beams. Default: the segmenter's
  // default minimum cluster size (perception/segmenter_options.h, min_points = 3); slammtt-eval
  // takes segmenter.min_points of the stack configuration when eval.min_beams is not set
  // (ReadStackEvalOptions, eval_log.h). 1 gives the world's own flag back.
  int min_beams = 3;
  // A MOVING object slower than this (true speed, m/s) stands still at that scan. 0 turns the
  // rule off.
  double min_moving_speed_mps = 0.2;
  // Where the laser sits on the robot (paper eq. 11: a forward, b left of the axle centre), to
  // draw a scan in the truth frame from the robot's true pose. Pictures only; slammtt-eval takes
  // estimator.sensor_forward_m / sensor_left_m of the stack configuration, and without them
  // (sensor_mount_given false) the log's LASER_GEOMETRY (EvalInput::laser_mount, with its yaw).
  double sensor_forward_m = 0.0;
  double sensor_left_m = 0.0;
  bool sensor_mount_given = false;
};

// The options schema of the evaluation: the keys of the `eval:` section, in the order of
// EvalOptions (the reader is ReadEvalOptions, eval_log.h; the table is docs/evaluation.md's,
// printed by slammtt-eval --options-table). The sensor mount is not among them: slammtt-eval
// takes it from the estimator's section or the log (ReadStackEvalOptions).
void VisitEvalOptions(OptionVisitor* visitor, EvalOptions* options);

// Empty when Evaluate() can use the options; otherwise one line naming the first bad option by
// its key ("gospa_alpha = 3: must be in (0, 2]"), and the sensor mount when it is not finite.
std::string CheckEvalOptions(const EvalOptions& options);

// The Markdown table of every key of the `eval:` section.
std::string EvalOptionsTable();

// Line landmarks (docs/evaluation.md, "Line landmarks"): a line matches a true surface within
// these of its direction and its line; a point landmark within kWallDistance_m of a wall is a
// piece of wall in the point map.
inline constexpr double kLineMatchMaxAngleDeg = 10.0;
inline constexpr double kLineMatchMaxDistance_m = 0.5;
inline constexpr double kWallDistance_m = 0.2;

// Upper bounds of the options, well beyond any use (a laser scan has a few thousand beams).
inline constexpr int kMaxMinBeams = 100000;
inline constexpr double kMaxMinMovingSpeedMps = 100.0;

struct TrajectoryResult {
  Pose2 anchor;              // estimate frame -> truth frame
  int64_t anchor_utime = 0;
  TrajectoryError error;
  std::vector<TimedPose> anchored;  // the estimate in the truth frame, at the scored times
  // For comparison with published figures (trajectory_error.h): ATE after the least-squares
  // alignment of the whole estimate (evo's --align), and the relative pose error.
  Pose2 least_squares_alignment;
  TrajectoryError aligned_error;
  RelativePoseError relative_error;
};

struct TrackingScan {
  int64_t utime = 0;
  // The truth set of this scan (ids of the visible movers in motion) and the CLEAR-MOT matches
  // (truth id, track id) made in it: the identity timeline's rows and colours.
  std::vector<int64_t> truth_ids;
  std::vector<std::pair<int64_t, int64_t>> matches;
  int num_truth = 0;
  int num_tracks = 0;  // confirmed MOVING tracks, don't-cares included
  int num_matches = 0;
  int num_dont_care = 0;  // tracks excused
  int num_few_beams = 0;  // movers hit by 1 to min_beams - 1 beams (scan log): not visible
  int num_standing = 0;   // visible movers standing still: not in the truth set
  double ospa_m = 0.0;
  double gospa_m = 0.0;
  bool had_tracks_message = true;
};

// An identity switch or a fragmentation with the utime of the scan where it is counted.
struct IdentitySwitchEvent {
  int64_t utime = 0;
  IdentitySwitch what;
};
struct FragmentationEvent {
  int64_t utime = 0;                  // tracked again
  int64_t untracked_since_utime = 0;  // the first scan of the gap
  Fragmentation what;
};

struct TrackingResult {
  std::vector<TrackingScan> scans;
  ClearMotSummary clear_mot;
  // IDF1 and HOTA (identity_metrics.h) on the same truth set and the same tracks, excused
  // tracks left out.
  IdentityScores identity;
  std::vector<IdentitySwitchEvent> identity_switches;
  std::vector<FragmentationEvent> fragmentations;
  // What the rules took out of the truth set over the scored scans, as (object, scan) pairs and
  // as distinct objects. A mover both standing and short of beams counts as short of beams.
  int64_t mover_scans_invisible = 0;   // not visible by the visibility rule (few beams included)
  int64_t mover_scans_few_beams = 0;   // hit by 1 to min_beams - 1 beams (scan log only)
  int64_t movers_few_beams = 0;
  int64_t mover_scans_standing = 0;    // visible and standing still
  int64_t movers_standing = 0;
  double ospa_mean_m = 0.0;
  double ospa_max_m = 0.0;
  double ospa_localisation_mean_m = 0.0;
  double ospa_cardinality_mean_m = 0.0;
  double gospa_mean_m = 0.0;
  double gospa_max_m = 0.0;
  int64_t gospa_missed = 0;
  int64_t gospa_false = 0;
  int64_t scans_without_tracks = 0;
  // Movers the scenery became (issue 13, item 5): the identities of reported MOVING tracks that
  // were false positives (matched to no counted truth object, not excused) in more than half of
  // the scans they were reported MOVING in; per minute of the TRACKS span (0 minutes: none).
  // With the people rule: confirmed movers that are not a person.
  int64_t false_mover_identities = 0;
  std::vector<int64_t> false_mover_ids;  // those identities, ascending
  double false_movers_per_minute = 0.0;
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
  // kUnjudged: a log without ground truth (nothing to judge it by).
  enum class Kind { kStatic, kMover, kUnexplained, kUnjudged } kind = Kind::kUnexplained;
};

// What the pictures of a log without GROUND_TRUTH draw of the robot (log_only_scene.h), in the
// estimator's map frame: every POSE, and the ODOMETRY anchored to the estimate at the first POSE
// (interpolated at its utime; a rigid transform, as the anchoring to the truth), or in its own
// frame when there is no POSE inside the odometry's time span.
struct LogOnlyScene {
  std::vector<TimedPose> estimate;
  std::vector<TimedPose> odometry;
  bool odometry_anchored_to_estimate = false;
  bool has_map = false;     // a MAP was accepted (it may hold no landmark)
  bool has_tracks = false;  // a TRACKS was accepted (it may hold no moving track)
};

// One scan as perception saw it (EvalInput::snapshot), with the truth of that moment.
struct ScanPicture {
  ScanSnapshot scan;
  // The sensor's true pose (truth frame) when GROUND_TRUTH has the scan's utime; without it the
  // picture is drawn in the sensor frame.
  std::optional<Pose2> sensor_pose;
  std::vector<TruthObjectSample> objects;  // truth at that moment (people, posts, discs)
  std::vector<TruthLeg> legs;
};

struct EvaluationReport {
  EvalOptions options;
  std::string source;
  // True when the log holds LASER_SCAN: visibility is beams_on_object >= min_beams.
  bool scan_log = false;
  // Objects the world marked visible at some scan but never visible by the min_beams rule (so
  // neither in the static truth of the map nor scored by the classification), per true class.
  int64_t statics_few_beams_only = 0;
  int64_t movers_few_beams_only = 0;
  int64_t truth_scans = 0;
  int64_t first_utime = 0;
  int64_t last_utime = 0;
  std::optional<TrajectoryResult> robot;     // POSE
  std::optional<TrajectoryResult> odometry;  // ODOMETRY
  std::optional<MapScore> map;
  // The smoother's outputs (slammtt-smoother), when the log has them: SMOOTHED_POSE scored as
  // POSE (anchored at its own first scan with a ground-truth pose), and the last SMOOTHED_MAP
  // as MAP, anchored by the smoothed trajectory's anchor.
  std::optional<TrajectoryResult> smoothed_robot;
  std::optional<MapScore> smoothed_map;
  // The last SMOOTHED_TRAJECTORY (every keyframe as the smoother estimated it at the end: the
  // smoothed trajectory in the smoothing sense, where smoothed_robot is the live, causal one),
  // at the keyframes that have a ground-truth scan, in the frame of smoothed_robot's anchor.
  std::optional<TrajectoryResult> final_smoothed_trajectory;
  // With a MAP and true surfaces (or line landmarks): the lines' score and the point landmarks
  // on walls (ids).
  std::optional<LineMapScore> line_map;
  std::vector<int64_t> point_landmarks_on_walls;
  std::optional<TrackingResult> tracking;
  std::optional<TrackingResult> tracking_with_coasting;  // confirmed tracks, coasting included
  std::optional<TrackingResult> people_tracking;
  std::optional<ClassificationSummary> classification;
  std::vector<std::string> notes;

  // For pictures, in the truth frame.
  std::vector<TimedPose> truth_trajectory;
  std::vector<std::vector<Eigen::Vector2d>> mover_paths;  // per moving object, all scans
  std::vector<IdentifiedPoint> static_objects;            // ever visible
  std::vector<IdentifiedPoint> unseen_static_objects;     // never visible
  std::vector<TruthSegment> static_segments;              // walls and furniture sides
  std::vector<AnchoredLandmark> landmarks;                // final map
  std::vector<EstimatedLine> lines;                       // final map's lines
  std::vector<TrackPath> track_paths;
  std::optional<ScanPicture> scan_picture;
  // Set when the log has no GROUND_TRUTH: then landmarks (kind kUnjudged), track_paths (every
  // confirmed MOVING track of every TRACKS message) and this are in the estimator's map frame,
  // and first_utime / last_utime span the log's POSE, ODOMETRY, TRACKS and MAP.
  std::optional<LogOnlyScene> log_only;
};

// Scores `input`. Throws std::invalid_argument for options out of range (thresholds not
// positive, order < 1, alpha outside (0, 2], min_beams outside [1, kMaxMinBeams],
// min_moving_speed_mps outside [0, kMaxMinMovingSpeedMps]).
// Throws std::invalid_argument naming the key for options CheckEvalOptions refuses.
EvaluationReport Evaluate(const EvalInput& input, const EvalOptions& options);

}  // namespace slammtt
