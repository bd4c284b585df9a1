// The estimator: one EKF over robot pose, static landmarks and moving objects, fed by odometry
// and point features, associating them with ML-RANSAC (paper Algorithm 2) or one of the two
// baselines. Pure library: no LCM, no I/O, no clock; randomness from the caller's generator.
//
// Per scan (ProcessScan), the steps of Algorithm 2 in order, each in its own file pair:
//   1. predict                the whole state to the scan time: robot by eq. 1 along the
//                             odometry since the previous scan (odometry_buffer.h; a robot that
//                             sends no odometry: by aligning the scan with the previous one,
//                             scan_alignment.h), movers by eqs. 6-8, landmarks unchanged
//                             (line 2: scan_prediction.h); with a local window, archived static
//                             landmarks near the robot re-enter the state (landmark_window.h);
//  1b. line landmarks        the scan's line features (walls) update the line landmarks and
//                             the pose, and start new line landmarks; the point features on a
//                             line landmark are dropped (line_landmarks.h; new walls start
//                             as candidate lines, line_candidates.h);
//   2. predict observations   of every object (eqs. 10-11, 20-21), once per state the scan
//                             passes through (observation_predictions.h);
//   3. gate                   Mahalanobis distances and the compatibility matrix J with gate d1
//                             (lines 3-4: scan_gating.h), then the budget of static-landmark
//                             updates (update_budget.h);
//   4. level 1                one update with the pairs J settles (lines 5-6: level1.h);
//   5. RANSAC, level 2        1-point RANSAC over the ambiguous pairs and an update with the
//                             best hypothesis' pairs gated by d1 (line 7: ransac_level.h);
//   6. level 3                a velocity jump for movers that lost their measurement in a turn
//                             (manoeuvres.h), then what is left with gate d2 > d1 (line 9:
//                             level3.h); then every velocity limited to its kind's plausible
//                             speed (people.h);
//   7. track management       hits and misses (line 11: hits_and_misses.h), and the identity
//                             take-overs of lost movers tagged at an earlier scan
//                             (reacquisition.h, step 2);
//   8. classification         static / moving with hysteresis, both ways (line 12:
//                             classification.h);
//   9. re-acquisition         new objects' possible continuations of lost movers
//                             (reacquisition.h, step 1), then pruning (line 11: pruning.h);
//  10. new objects            from measurements outside gate dn of every object (line 13:
//                             new_objects.h); with a local window, static landmarks far from
//                             the robot then leave the state for its archive
//                             (landmark_window.h).
// The levels share the assignment and the update of chosen pairs (association.h).
// Baselines, same code paths where they share them (Options::mode):
//   kStaticNearestNeighbour  plain EKF-SLAM assuming a static world (the paper's Fig. 5):
//                every object is a static landmark, mapped from its first sighting and never
//                removed; each measurement goes to its nearest landmark inside d1 (one-to-one,
//                the closer measurement wins); a measurement outside gate dn of every landmark
//                starts a new one. No RANSAC, no level 3, no classification, no miss
//                accounting, no pruning, no confirmation. Shares the prediction, gating,
//                update and new-landmark code;
//   kRansacAllPairs          plain RANSAC: hypotheses drawn from every measurement-object pair
//                and judged on every pair, with no compatibility matrix and no first level.
//
// Bad input never breaks it, and every case is counted (EstimatorCounters) and described
// (last_event()): non-finite or out-of-range features are rejected, and a scan's features
// beyond max_features_per_scan are dropped (the nearest are kept); odometry that no P3-DX can
// produce (odometry_plausibility.h) is rejected; odometry or scans older than the last
// processed one are dropped; one utime that jumps is dropped, and only several in a row make a
// new time base (time_base.h); a time gap above max_time_gap_s inflates the robot and mover
// uncertainty instead of trusting a long prediction; a scan with no odometry since the
// previous one predicts with the last known velocities and inflated noise; an empty scan is a
// valid scan; max_objects caps the number of objects. Should the state still become
// non-finite, it is recovered before anything is published (state_recovery.h).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/feature_validation.h"
#include "estimator/gating.h"
#include "estimator/landmark_window.h"
#include "estimator/ml_ransac.h"
#include "estimator/odometry_buffer.h"
#include "estimator/odometry_plausibility.h"
#include "estimator/scan_alignment.h"
#include "estimator/scan_prediction.h"
#include "estimator/slam_state.h"
#include "estimator/smoother_feedback.h"
#include "estimator/static_observations.h"
#include "estimator/step_counts.h"
#include "estimator/time_base.h"

namespace slammtt {

struct ScanInput {
  int64_t utime = 0;
  std::vector<FeatureReading> features;
  std::vector<LineReading> lines;  // walls and furniture sides (line_landmarks.h)
};

// The six sub-stages of one scan, in order (the names of STAGE_TIMING).
enum class Substage { kPredict, kGating, kLevel1, kRansac, kLevel23, kTrackManagement };
const char* SubstageName(Substage substage);

// Told when each sub-stage of a scan ends (the stage adapter times them; the library has no
// clock).
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void SubstageDone(Substage substage) = 0;
};

struct ObjectEstimate {
  int64_t id = 0;
  ObjectClass object_class = ObjectClass::kUndecided;
  ObjectKind kind = ObjectKind::kOther;
  bool confirmed = false;
  // Honest reporting (track_management.h): measured in this scan, time since the last
  // measurement, and whether it counts as a reported track (a tentative person track in the
  // scan it was born in too, people.h: ReportedAtBirth).
  bool measured = false;
  double coasting_s = 0.0;
  bool reported = false;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  // (x, y, vx, vy)
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;
  int hits = 0;
};

// A line landmark of the map frame (line_model.h), with its observed extent's end points.
struct LineEstimate {
  int64_t id = 0;
  Eigen::Vector2d line = Eigen::Vector2d::Zero();  // (rho_m, alpha_rad)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();  // extent end points, map frame
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  int hits = 0;
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;
};

struct ScanResult {
  bool processed = false;       // false: dropped (out of order)
  int64_t utime = 0;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  std::vector<ObjectEstimate> objects;
  // The static landmarks of the local window's archive (landmark_window.h), by id: part of the
  // map, not of the state (never measured in this scan).
  std::vector<ObjectEstimate> archived_landmarks;
  std::vector<LineEstimate> lines;
  StepCounts counts;
  // For the smoother (smoother_input.h): the robot's motion the prediction applied, and the
  // measurements associated with point landmarks or objects that may become one (tentative),
  // and the sightings that started such objects (static_observations.h, new_objects.h).
  RobotMotion motion;
  std::vector<StaticObservation> static_observations;
};

// Cumulative counters (estimator_status_t).
struct EstimatorCounters {
  int64_t scans_processed = 0;
  int64_t odometry_processed = 0;
  int64_t odometry_rejected = 0;       // non-finite or physically implausible odometry
  int64_t features_rejected = 0;
  int64_t messages_out_of_order = 0;
  int64_t time_gaps = 0;
  int64_t scans_without_odometry = 0;
  int64_t object_cap_hits = 0;
  int64_t hypotheses_generated = 0;
  int64_t updates_failed = 0;
  int64_t static_updates_skipped = 0;
  int64_t restarts = 0;                // new time bases back (time_base.h): started over
  int64_t smoother_feedbacks = 0;      // smoothed estimates applied (smoother_feedback.h)
  int64_t smoother_feedbacks_stale = 0;  // not applied: their scan no longer in the history
  int64_t time_jumps_rejected = 0;     // messages whose utime jumped, not (yet) a new time base
  int64_t odometry_frame_jumps = 0;    // odometry re-anchored in a new frame
  int64_t state_recoveries = 0;        // scans that ended non-finite and were recovered
  int64_t features_over_cap = 0;       // beyond max_features_per_scan, dropped
  int64_t ransac_budget_cuts = 0;      // scans whose RANSAC stopped at ransac_max_pair_tests
  int64_t lines_rejected = 0;          // bad line features
  int64_t lines_refused = 0;           // new line landmarks refused by lines_max_landmarks
};

class Estimator {
 public:
  // Throws std::invalid_argument with CheckEstimatorOptions()'s message for unusable options.
  explicit Estimator(const EstimatorOptions& options);

  // Buffers one odometry reading. Returns false when it is dropped (non-finite, or not newer
  // than the previous reading); the counters and last_event() say why.
  bool AddOdometry(const OdometryReading& reading);

  // Runs Algorithm 2 on one scan. A scan not newer than the previous processed one is dropped
  // (result.processed = false). `rng` drives RANSAC; `observer` (optional) hears the sub-stages.
  ScanResult ProcessScan(const ScanInput& scan, std::mt19937_64* rng,
                         StepObserver* observer = nullptr);

  // From the next scan on, the laser geometry of `options` (sensor mount, field of view,
  // max_range_m; laser_geometry.h) replaces the one the estimator was built with; nothing else
  // of `options` is read, and the state is kept (landmarks live in the map frame). Throws
  // std::invalid_argument with CheckEstimatorOptions()'s message for unusable options.
  void SetLaserGeometry(const EstimatorOptions& options);

  // The smoother's estimate of an earlier (or the newest) scan (smoother_feedback.h): the
  // robot's pose, carried forward along the filter's motion since that scan, and the confirmed
  // static landmarks the smoother holds move to it; the covariance is kept. Not applied
  // (counts.applied false) when the scan is not among the last 64 processed or precedes the
  // last correction or a restart. Applied whatever options().smoother_feedback says: that
  // option tells the stage whether to call it.
  FeedbackCounts ApplySmoothedEstimate(const SmoothedEstimate& smoothed);

  const EstimatorCounters& counters() const { return counters_; }
  // Description of the last unusual event ("" if none yet).
  const std::string& last_event() const { return last_event_; }
  const SlamState& state() const { return state_; }
  // The landmarks out of the state (landmark_window.h; empty without a window).
  const LandmarkArchive& archive() const { return archive_; }
  const EstimatorOptions& options() const { return options_; }
  int NumObjectsOfClass(ObjectClass object_class, bool confirmed_only) const;
  int NumTentative() const;

 private:
  // False (and the scan counted and described) when the scan's utime is late or a jump; a
  // confirmed new time base back starts the estimation over first.
  bool AcceptScanTime(int64_t utime);
  // The verdict of `clock` on a message of `what` at `utime`, counted and described; true when
  // the message is to be used (after a restart for a new time base back).
  bool AcceptTime(const char* what, int64_t utime, StreamClock* clock);
  // Starts the estimation over: the state at the initial pose, both streams forgotten.
  void StartOver();
  // The end of every scan: a non-finite state is recovered (state_recovery.h), counted and
  // described.
  void EnsureFiniteState(int64_t utime, StepCounts* counts);
  ScanInterval IntervalTo(int64_t utime) const;
  // The scan's features validated (feature_validation.h); rejections counted and described.
  ValidatedFeatures TakeFeatures(const std::vector<FeatureReading>& features, StepCounts* counts);
  // The steps of ProcessScan, each one line (or lines) of Algorithm 2; ScanInProgress
  // (estimator.cc) carries what one step hands on to the next.
  struct ScanInProgress;
  // Line 2: Predict, then UpdateLines and DropPointsOnLines.
  void PropagateState(const ScanInput& scan, ScanInProgress* s);
  // With no odometry received and scan_alignment_enabled: the robot's motion since the previous
  // scan from aligning the scan with it (scan_alignment.h); the scan is kept in `s` to be the
  // next one's reference (FinishScan). nullopt otherwise, and at the first scan.
  std::optional<ScanAlignment> AlignWithPreviousScan(const ScanInput& scan,
                                                     ScanInProgress* s) const;
  // Lines 3-4 (scan_gating.h), and the budget of updates (update_budget.h).
  void GateMeasurements(ScanInProgress* s);
  // Lines 5-6 (level1.h; the static-world baseline: nearest_neighbour.h). Returns the pairs J
  // leaves ambiguous (none in the baselines).
  std::vector<Candidate> UpdateFirstLevel(ScanInProgress* s);
  // Line 7 a-d (ransac_level.h): RANSAC's best hypothesis over `ambiguous`, counted; a cut by
  // ransac_max_pair_tests described. None in the static-world baseline.
  RansacOutcome FindRansacConsensus(const std::vector<Candidate>& ambiguous,
                                    std::mt19937_64* rng, ScanInProgress* s);
  // Line 7 e: the consensus' pairs, gated by d1, update the state (association.h).
  void UpdateSecondLevel(const RansacOutcome& ransac, ScanInProgress* s);
  // Line 9 when level 3 is on (manoeuvres.h, level3.h); then every speed limited to its kind's
  // (people.h).
  void UpdateThirdLevel(ScanInProgress* s);
  // Lines 11-13: hits and misses, take-overs, classification, re-acquisition tags, pruning,
  // new objects (steps 7-10 above). Returns the scan's measurements of point landmarks (and
  // tentative ones), taken right after classification (static_observations.h), then the
  // sightings that started new objects (new_objects.h).
  std::vector<StaticObservation> ManageTracks(ScanInProgress* s);
  // The local window (landmark_window.h): archived landmarks near the robot's predicted pose
  // re-enter the state before gating; far ones leave it at the end of the scan.
  void RestoreNearbyLandmarks(ScanInProgress* s);
  void ArchiveDistantLandmarks(ScanInProgress* s);
  // The scan's problems reported, the state made finite (EnsureFiniteState); without odometry
  // the scan becomes the next one's alignment reference.
  void FinishScan(ScanInProgress* s);
  // Step 1 (scan_prediction.h), with what it made up for counted and described; `aligned`
  // (optional): the motion without odometry (AlignWithPreviousScan).
  void Predict(int64_t utime, const ScanInterval& interval, const ScanAlignment* aligned);
  // Step 1b (line_landmarks.h): the walls update the pose and the line landmarks.
  void UpdateLines(const ScanInput& scan, StepCounts* counts);
  // Takes the point features that lie on a line landmark out of the scan's measurements
  // (line_landmarks.h: PointsOnLineLandmarks): pieces of walls are not point landmarks.
  void DropPointsOnLines(ValidatedFeatures* features, StepCounts* counts) const;
  // The object cap and numerically unusable updates of the scan, counted and described.
  void ReportScanProblems(int64_t utime, const StepCounts& counts);
  // The pose and every object as the scan leaves them.
  void ReportEstimate(int64_t utime, ScanResult* result) const;
  void Event(const std::string& text) { last_event_ = text; }
  TimeJumpLimits time_jump_limits() const;

  EstimatorOptions options_;
  SlamState state_;
  LandmarkArchive archive_;
  EstimatorCounters counters_;
  std::string last_event_;
  std::optional<int64_t> last_scan_utime_;  // of the last processed scan
  StreamClock scan_clock_;
  StreamClock odometry_clock_;
  OdometryPlausibility odometry_check_;
  OdometryBuffer odometry_;
  ScanToScanMotion scan_motion_;  // without odometry (scan_alignment.h)
  Eigen::Vector3d last_finite_pose_;
  Eigen::Matrix3d last_finite_pose_covariance_ = Eigen::Matrix3d::Zero();
  std::vector<LineCandidate> line_candidates_;  // straight runs not yet line landmarks
  RobotMotion last_motion_;  // of the last prediction (ScanResult::motion)
  ScanPoseHistory pose_history_;  // the pose after each recent scan (smoother feedback)
  int64_t next_id_ = 1;
};

}  // namespace slammtt
