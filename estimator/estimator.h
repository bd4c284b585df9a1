// The estimator: one EKF over robot pose, static landmarks and moving objects, fed by odometry
// and point features, associating them with ML-RANSAC (paper Algorithm 2) or one of the two
// baselines. Pure library: no LCM, no I/O, no clock; randomness from the caller's generator.
//
// Per scan (ProcessScan), in the order of Algorithm 2:
//   predict      robot by eq. 1 along the odometry received since the previous scan, movers by
//                eqs. 6-8, landmarks unchanged (eq. 9, block-wise: ekf_prediction.h);
//   gating       predicted observations (eqs. 10-11, 20-21), Mahalanobis distances and the
//                compatibility matrix J with gate d1 (lines 3-4: gating.h);
//   level1       one update with the pairs J settles (lines 5-6);
//   ransac       1-point RANSAC over the ambiguous pairs (line 7.a-d: ml_ransac.h);
//   level2_3     update with the best hypothesis' pairs gated by d1 (line 7.e), then the
//                optional third level with gate d2 > d1 (line 9), after giving the movers
//                that lost their measurement in a turn a velocity jump (manoeuvre);
//   track_management  hits and misses, static/moving classification with hysteresis (line 12,
//                motion_classifier.h), pruning (line 11), new objects from measurements
//                outside gate dn of every object (line 13: moving, zero velocity, large
//                velocity covariance; track_management.h).
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
// (last_event()): non-finite or out-of-range features are rejected; odometry or scans older
// than the last processed one are dropped; a time gap above max_time_gap_s inflates the robot
// and mover uncertainty instead of trusting a long prediction; a scan with no odometry since
// the previous one predicts with the last known velocities and inflated noise; an empty scan
// is a valid scan; max_objects caps the number of objects.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "estimator/gating.h"
#include "estimator/ml_ransac.h"
#include "estimator/motion_classifier.h"
#include "estimator/point_measurement.h"
#include "estimator/range_bearing_model.h"
#include "estimator/robot_motion_model.h"
#include "estimator/slam_state.h"
#include "estimator/track_management.h"

namespace slammtt {

enum class AssociationMode { kMlRansac, kStaticNearestNeighbour, kRansacAllPairs };

// How close to the edge of the field of view a feature's angular extent must come to count as
// cut by it (EstimatorOptions::edge_of_view_sigma_m): two beams of the paper's 0.5-degree laser,
// as the outermost beam that hit the object may be up to one spacing inside the edge.
inline constexpr double kEdgeOfViewMargin_rad = 1.0 * M_PI / 180.0;

struct EstimatorOptions {
  AssociationMode mode = AssociationMode::kMlRansac;
  Eigen::Vector3d initial_pose = Eigen::Vector3d::Zero();  // map frame = start pose

  // Sensor (paper eq. 11 offset; section 5.1 noise and range).
  SensorMount sensor;
  double default_range_sigma_m = 0.2;            // paper 5.1: 0.2 m
  double default_bearing_sigma_rad = 2.0 * M_PI / 180.0;  // paper 5.1: 2 degrees
  bool use_feature_covariance = true;            // a feature's own R when it carries one
  double min_range_sigma_m = 0.0;                // floors applied to a feature's own R
  double min_bearing_sigma_rad = 0.0;
  double min_range_m = 0.01;                     // features outside are rejected
  double max_range_m = 30.0;                     // paper 5.1: 30 m
  double field_of_view_rad = 2.0 * M_PI;         // for "in view" (static landmark pruning)
  // Range up to which a person-sized object is expected to produce a feature (0: max_range_m).
  // With raw scans the segmenter needs a few beams on an object, so a 0.5 m person is detected
  // up to about 0.5 m / (min_points * resolution): 19 m at 0.5 degrees and 3 points.
  double detection_range_m = 0.0;
  // A cluster that reaches the edge of a limited field of view is only the visible part of its
  // object: the rest lies beyond the edge, so its centre can be off by up to about one object
  // radius, along the range and across it (a person leaving a 180-degree view beside the robot:
  // 0.15-0.25 m on s2-lobby). Such a feature gets this standard deviation added in both
  // directions (range variance + s^2, bearing variance + min(s / range, pi)^2). A feature is at the
  // edge when its angular extent, atan(width / 2 / range) either side of its bearing, comes
  // within kEdgeOfViewMargin_rad of the edge. 0 disables it.
  double edge_of_view_sigma_m = 0.3;

  // Motion models.
  OdometryNoiseOptions odometry_noise;
  // The odometry's systematic heading drift b [rad per metre travelled], estimated as a state
  // (slam_state.h, ekf_prediction.h): prior b ~ N(0, sigma^2). Its physical origin is a
  // difference of the two wheels' effective diameters (UMBmark's type-B error, Borenstein and
  // Feng 1996): a relative difference e on an axle of length L turns the odometry by e / L
  // radians per metre. The P3-DX's wheels (195 mm) are about 0.33 m apart (docs/world.md,
  // odometry.axle_length_m); pneumatic tyres differ by up to about 0.5 % in effective
  // diameter with load and pressure, which gives |b| up to 0.005 / 0.33 = 0.015 rad/m: the
  // default puts that at 2 sigma. 0 turns the drift state off (b stays exactly 0).
  double heading_drift_sigma_rad_per_m = 0.0075;
  // Random walk of b [rad^2/m^2 per metre travelled]: 1e-8 lets b change by 1e-3 rad/m (a
  // 0.03 % change of a wheel's size) over 100 m, the order of a tyre warming up or losing
  // pressure over a run. Ignored when the prior sigma is 0.
  double heading_drift_walk_var_per_m = 1e-8;
  // sigma_Q of eq. 8. A MOVING object walks at a steady velocity between turns (its turns are
  // manoeuvres, below); an UNDECIDED one gets a more forgiving model while its velocity is
  // judged, so that its velocity covariance does not become overconfident about a static
  // object seen from a drifting robot.
  double mover_acceleration_sigma_mps2 = 0.02;
  double undecided_acceleration_sigma_mps2 = 0.2;
  double new_object_velocity_sigma_mps = 1.0;    // prior of a new object's velocity
  // Manoeuvres: a MOVING object with no measurement after level 2 while an
  // unassigned measurement lies inside its gate dn gets a velocity jump of this standard
  // deviation over the last interval (ekf_prediction.h: AddVelocityJump) before level 3 tries
  // again. 0 disables it.
  double manoeuvre_velocity_sigma_mps = 1.5;

  // Robustness.
  double max_time_gap_s = 1.0;                   // longer gaps inflate the uncertainty
  // The longest interval one prediction covers: a longer gap (the process was paused, a
  // corrupted utime years ahead) is inflated, and movers and extrapolated motion predicted, as
  // if it were this long. Minutes without a measurement leave a person anywhere and a robot
  // without odometry beyond what an EKF can recover; unbounded, the inflation (0.5 m/s, 0.2
  // rad/s, 1 m/s per mover, each times the gap) drives the covariance's condition number past
  // what double precision updates stay positive semi-definite at (a 2e4 s gap did).
  double max_prediction_s = 30.0;
  // A message older than the newest of its stream by more than this is not a late message but
  // a new time base: a log played again or another log (lcm-logplayer), a restarted simulator,
  // the robot's clock stepped back, or the return to normal after one corrupted far-future
  // utime. The estimator starts over from the initial pose with an empty map (track ids keep
  // counting up, the counters keep counting) instead of dropping everything until the clock
  // passes its newest utime. Shorter steps back are out-of-order messages and are dropped: 2 s
  // is far beyond any delivery delay (LCM delivers within milliseconds; a scan's FEATURES come
  // within its processing time) and shorter than any log worth replaying.
  double time_jump_back_restart_s = 2.0;
  double gap_robot_position_sigma_mps = 0.5;     // added robot std per second of gap
  double gap_robot_heading_sigma_radps = 0.2;
  double gap_mover_velocity_sigma_mps = 1.0;     // added to every mover's velocity std
  double extrapolation_speed_sigma_mps = 0.3;    // noise of motion without odometry, per
  double extrapolation_turn_sigma_radps = 0.3;   // second of extrapolation
  int max_objects = 500;

  // Association (Algorithm 2). Gates are NIS thresholds (chi-square, 2 dof).
  double gate_d1_chi2 = 9.21;                    // 99 %
  bool level3 = true;
  double gate_d2_chi2 = 13.82;                   // 99.9 %
  double new_object_gate_dn_chi2 = 20.0;
  RansacOptions ransac;
  int update_group_size = 32;                    // observations per batch update (ekf_update.h)
  // Per-scan budget of static-landmark updates (0: no limit). Every measurement is still gated
  // and associated (hits, misses, classification and new objects see every association), and
  // objects with velocity states (moving, undecided) always update; but of the static
  // landmarks that have a candidate pair this scan, only the K least recently updated may
  // update the state (ties: lower object index). The choice depends on the state's
  // book-keeping only, never on the measurements' values, so dropping the others keeps the
  // filter consistent: it only gives up information. The dense update costs O(n^2) per
  // observation, so this bounds the cost of a scan that sees hundreds of landmarks
  // (docs/estimator.md, "Speed").
  int max_static_updates_per_scan = 32;

  TrackManagementOptions tracks;
  MotionClassifierOptions classifier;
};

// Empty when the options are usable, else one line naming the first bad option.
std::string CheckEstimatorOptions(const EstimatorOptions& options);
const char* AssociationModeName(AssociationMode mode);

// One odometry_t as the estimator needs it: the base's integrated pose in its own (drifting)
// odometry frame and its velocities.
struct OdometryReading {
  int64_t utime = 0;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();  // x_m, y_m, heading_rad
  double linear_mps = 0.0;
  double angular_radps = 0.0;
};

// One feature_t as received (validated by the estimator).
struct FeatureReading {
  double range_m = 0.0;
  double bearing_rad = 0.0;
  double range_var_m2 = 0.0;   // 0 (with bearing_var 0): use the default noise
  double bearing_var_rad2 = 0.0;
  double range_bearing_cov_m_rad = 0.0;
  double width_m = 0.0;        // extent of the cluster (0: a point), for occlusion reasoning
};

struct ScanInput {
  int64_t utime = 0;
  std::vector<FeatureReading> features;
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
  bool confirmed = false;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  // (x, y, vx, vy)
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;
  int hits = 0;
};

// What one scan did.
struct StepCounts {
  int features = 0;             // received
  int features_rejected = 0;
  int features_at_edge_of_view = 0;  // cut by the edge of the field of view (R inflated)
  int level1_updates = 0;
  int level2_updates = 0;
  int level3_updates = 0;
  int manoeuvres = 0;           // movers given a velocity jump before level 3
  int hypotheses = 0;
  int new_objects = 0;
  int reacquired = 0;           // lost movers seen again (identity taken over, track_management.h)
  int objects_refused = 0;      // by the object cap
  int pruned = 0;
  int became_moving = 0;
  int became_static = 0;
  int started_moving = 0;
  int updates_failed = 0;
  int static_updates_skipped = 0;  // associated landmarks left out by the per-scan budget
};

struct ScanResult {
  bool processed = false;       // false: dropped (out of order)
  int64_t utime = 0;
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  std::vector<ObjectEstimate> objects;
  StepCounts counts;
};

// Cumulative counters (estimator_status_t).
struct EstimatorCounters {
  int64_t scans_processed = 0;
  int64_t odometry_processed = 0;
  int64_t odometry_rejected = 0;       // non-finite odometry
  int64_t features_rejected = 0;
  int64_t messages_out_of_order = 0;
  int64_t time_gaps = 0;
  int64_t scans_without_odometry = 0;
  int64_t object_cap_hits = 0;
  int64_t hypotheses_generated = 0;
  int64_t updates_failed = 0;
  int64_t static_updates_skipped = 0;
  int64_t restarts = 0;                // time_jump_back_restart_s: starts over on a new time base
};

class Estimator {
 public:
  explicit Estimator(const EstimatorOptions& options);

  // Buffers one odometry reading. Returns false when it is dropped (non-finite, or not newer
  // than the previous reading); the counters and last_event() say why.
  bool AddOdometry(const OdometryReading& reading);

  // Runs Algorithm 2 on one scan. A scan not newer than the previous processed one is dropped
  // (result.processed = false). `rng` drives RANSAC; `observer` (optional) hears the sub-stages.
  ScanResult ProcessScan(const ScanInput& scan, std::mt19937_64* rng,
                         StepObserver* observer = nullptr);

  const EstimatorCounters& counters() const { return counters_; }
  // Description of the last unusual event ("" if none yet).
  const std::string& last_event() const { return last_event_; }
  const SlamState& state() const { return state_; }
  const EstimatorOptions& options() const { return options_; }
  int NumObjectsOfClass(ObjectClass object_class, bool confirmed_only) const;
  int NumTentative() const;

 private:
  struct OdometryCursor {
    int64_t utime = 0;
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();
    double linear_mps = 0.0;
    double angular_radps = 0.0;
  };

  // Prediction to the scan at `utime`: `gap_s` since the previous scan, of which `dt` (at most
  // max_prediction_s) is predicted, inflated and extrapolated.
  void Predict(int64_t utime, bool first_scan, double gap_s, double dt);
  // Accepted measurements, and the width of each in `widths`.
  std::vector<PointMeasurement> ValidateFeatures(const std::vector<FeatureReading>& features,
                                                 StepCounts* counts, std::vector<double>* widths);
  void Event(const std::string& text) { last_event_ = text; }
  // True (and the estimator started over, counted and described) when `utime` lies more than
  // time_jump_back_restart_s before `newest_utime` of its stream.
  bool RestartOnJumpBack(const char* what, int64_t utime,
                         const std::optional<int64_t>& newest_utime);

  EstimatorOptions options_;
  SlamState state_;
  EstimatorCounters counters_;
  std::string last_event_;
  std::optional<int64_t> last_scan_utime_;
  std::optional<int64_t> last_odometry_utime_;
  std::optional<OdometryCursor> cursor_;
  std::deque<OdometryReading> odometry_;  // readings newer than the cursor, oldest first
  int64_t next_id_ = 1;
};

}  // namespace slammtt
