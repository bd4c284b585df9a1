// The smoother fed scan by scan from the estimator (issue 14, item 2; docs/smoother.md,
// "In the stack"): what slammtt-smoother runs on every SMOOTHER_INPUT. Pure: no LCM, no clock.
//
// Per scan (SmootherScanInput, estimator/smoother_input.h):
//  1. A scan that does not continue (the estimator's first scan, or its first after starting
//     over) starts a new problem: keyframe 0 at the filter's pose with a prior of the filter's
//     covariance (plus the prior floor: the filter knows its first pose exactly).
//  2. Landmarks that left the estimator's static map leave the problem (Smoother::RemoveLandmark).
//  3. The scan's odometry increment is composed onto the motion since the last keyframe (the
//     covariances propagated through the composition's Jacobians).
//  4. The scan is a keyframe when the robot moved keyframe_distance_m, turned
//     keyframe_rotation_rad or keyframe_interval_s passed since the last keyframe (all three 0:
//     every scan). A keyframe adds its pose at the last keyframe's estimate composed with the
//     motion, the odometry factor between them (the motion's covariance plus the odometry floor:
//     the motion model has no lateral noise, so its covariance alone can be singular), and a
//     range-bearing factor (paper eqs. 10-11 with the mount) per static observation, a new
//     landmark starting where its first observation puts it. A tentative observation of an
//     object that is not in the problem yet is held with its keyframe (at most
//     max_held_observations per object) until the object's first confirmed static observation,
//     which adds the landmark and every held observation; a removal drops what is held.
//     The observations of a scan between keyframes (between_keyframe_observations) are
//     converted into positions in the last keyframe's frame through the motion since it (the
//     mount composed with it, the motion's covariance added to R) and fused per landmark; at
//     the next keyframe each landmark's fused position is one relative-position factor on the
//     last keyframe. Then one incremental Update, and a batch Optimize every
//     optimize_every_keyframes keyframes.
//  5. The robot's smoothed pose at the scan: the last keyframe's estimate composed with the
//     motion since.
// Bad input (a non-finite number, a covariance that is not positive definite, a range <= 0) is
// refused by the library with a one-line reason; the factor is left out, counted and the reason
// kept (last_error()), and the rest of the scan goes on. A scan older than the last one is
// dropped (counted).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/options_schema.h"
#include "estimator/smoother_input.h"
#include "smoother/smoother.h"

namespace slammtt {

struct KeyframeSmootherOptions {
  // Keyframe rule; all three 0: every scan is a keyframe.
  double keyframe_distance_m = 0.0;
  double keyframe_rotation_rad = 0.0;
  double keyframe_interval_s = 0.0;
  // A batch Optimize (Levenberg-Marquardt to convergence) every this many keyframes (0: never;
  // every keyframe has its incremental Update anyway).
  int optimize_every_keyframes = 0;
  // Standard deviations added in quadrature to the odometry's per-scan increment covariance
  // (and to the first keyframe's prior): the motion model has no sideways noise.
  double odometry_min_sigma_m = 0.002;
  double odometry_min_sigma_rad = 0.001;
  // Factors on the variances of the estimator's per-scan increment covariance, along the
  // robot's heading, sideways and in heading (before the floor above is added): the motion
  // model's noise is sized to hold the wheel-size bias as well (docs/smoother.md, "Measured").
  double odometry_variance_scale_forward = 1.0;
  double odometry_variance_scale_sideways = 1.0;
  double odometry_variance_scale_heading = 1.0;
  double prior_min_sigma_m = 0.001;
  double prior_min_sigma_rad = 0.001;
  // Tentative observations held per object (the oldest are dropped beyond).
  int max_held_observations = 400;
  // Observations of the scans between keyframes: used as range-bearing factors on the last
  // keyframe through the motion since it (the laser's mount composed with that motion), their
  // covariance R plus the motion's uncertainty seen in range and bearing, times
  // between_keyframe_variance_scale on that added part (false: left out, as before).
  bool between_keyframe_observations = true;
  double between_keyframe_variance_scale = 1.0;
  // Marginal covariances of the last pose and of every landmark (solves through the factor).
  bool covariances = true;
  // The stage publishes the map (with the landmarks' covariances, the costly part) at every
  // this many keyframes (smoother_stage.h).
  int map_every_keyframes = 8;
  // The incremental solver (Smoother::Update). The stack reads no update's chi^2, so it is not
  // computed (a pass over every factor per keyframe).
  SmootherOptions solver = [] {
    SmootherOptions o;
    o.update_chi_square = false;
    return o;
  }();
};

// The schema of the options (common/options_schema.h; keys of the `smoother:` section, the
// solver's with the prefix `solver_`).
void VisitKeyframeSmootherOptions(OptionVisitor* visitor, KeyframeSmootherOptions* options);
// "" when the options are usable, else the first problem in one line.
std::string CheckKeyframeSmootherOptions(const KeyframeSmootherOptions& options);

struct KeyframeSmootherCounters {
  int64_t scans = 0;
  int64_t keyframes = 0;
  int64_t restarts = 0;                // new problems after the first
  int64_t scans_out_of_order = 0;      // not newer than the last scan: dropped
  int64_t observations_used = 0;
  // Of scans that were no keyframe: attached to the last keyframe through the motion since
  // (between_keyframe_observations), else not used.
  int64_t observations_between_keyframes = 0;
  int64_t observations_held = 0;       // tentative ones held for a possible landmark
  int64_t held_observations_dropped = 0;  // held ones of objects removed, or beyond the cap
  int64_t landmarks_removed = 0;
  int64_t inputs_refused = 0;          // factors, variables or removals the library refused
  int64_t solves_failed = 0;
  int64_t batch_optimizations = 0;
};

// What one scan did.
struct SmoothedScan {
  bool processed = false;  // false: dropped (out of order)
  bool keyframe = false;
  int64_t utime = 0;
  // The robot at the scan (map frame) and its covariance (zero when covariances are off or
  // cannot be computed).
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  SolveReport update;                  // of the keyframe's Update
  std::optional<SolveReport> batch;    // when a batch Optimize ran
};

struct SmoothedLandmark {
  int64_t id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // zero when covariances are off
};

class KeyframeSmoother {
 public:
  // Throws std::invalid_argument with CheckKeyframeSmootherOptions()'s message.
  explicit KeyframeSmoother(const KeyframeSmootherOptions& options);

  SmoothedScan AddScan(const SmootherScanInput& scan);

  // Every landmark of the problem (in the order added), at the current estimate.
  std::vector<SmoothedLandmark> Landmarks();
  // Every keyframe's (utime, pose) at the current estimate, in order.
  std::vector<std::pair<int64_t, Eigen::Vector3d>> Keyframes() const;

  const KeyframeSmootherCounters& counters() const { return counters_; }
  const std::string& last_error() const { return last_error_; }
  const Smoother* smoother() const { return smoother_.get(); }

 private:
  void StartProblem(const SmootherScanInput& scan);
  void AccumulateMotion(const SmootherScanInput& scan);
  bool IsKeyframe(int64_t utime) const;
  void AddKeyframe(const SmootherScanInput& scan, SmoothedScan* out);
  // Every observation of the scan as a factor on the last keyframe, the laser at `mount` in
  // that keyframe's frame.
  void AddObservations(const SmootherScanInput& scan, const SensorMount& mount);
  void AddObservations(const SmootherScanInput& scan) { AddObservations(scan, scan.mount); }
  // The observations of a scan between keyframes: those of landmarks in the problem are fused
  // per landmark into one position in the last keyframe's frame (information-weighted, each
  // converted with its covariance), added as one relative-position factor per landmark when
  // the next keyframe comes (FlushFused): one factor per landmark and keyframe instead of one
  // per scan, so that the cost per keyframe stays what it was; the others as AddObservations.
  // Each observation's covariance first gets `extra_covariance` (over range, bearing: the
  // motion's since the keyframe).
  void FuseObservations(const SmootherScanInput& scan, const SensorMount& mount,
                        const std::vector<Eigen::Matrix2d>& extra_covariance);
  void FlushFused();
  // The laser of a scan between keyframes in the last keyframe's frame, and what the motion's
  // covariance adds to each observation's (range, bearing) covariance.
  SensorMount MountSinceKeyframe(const SensorMount& mount) const;
  std::vector<Eigen::Matrix2d> MotionCovarianceOfObservations(const SmootherScanInput& scan,
                                                              const SensorMount& mount) const;
  void Hold(const StaticObservation& observation, const SensorMount& mount);
  // Adds the landmark (where its first held, else this, observation puts it) and its held
  // observations; false when it cannot be added.
  bool AddLandmarkWithHeld(const StaticObservation& observation, const SensorMount& mount);
  void AddRangeBearing(PoseId pose, const StaticObservation& observation,
                       const SensorMount& mount);
  void RemoveLandmarks(const std::vector<int64_t>& ids);
  void Refused(const std::optional<std::string>& error);
  void Solve(SmoothedScan* out);
  void FillPose(SmoothedScan* out);

  KeyframeSmootherOptions options_;
  std::unique_ptr<Smoother> smoother_;
  KeyframeSmootherCounters counters_;
  std::string last_error_;
  std::optional<int64_t> last_utime_;
  // The last keyframe and the motion since (in its frame) with its covariance.
  std::vector<int64_t> keyframe_utimes_;  // by keyframe id (ids count from 0 in each problem)
  // The newest keyframe (-1 before the first) and its utime, from keyframe_utimes_.
  PoseId LastKeyframe() const { return static_cast<PoseId>(keyframe_utimes_.size()) - 1; }
  int64_t LastKeyframeUtime() const { return keyframe_utimes_.back(); }
  Eigen::Vector3d motion_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d motion_covariance_ = Eigen::Matrix3d::Zero();
  int keyframes_since_batch_ = 0;
  std::optional<Eigen::Matrix3d> last_keyframe_covariance_;
  struct Held {
    PoseId keyframe = 0;
    StaticObservation observation;
    SensorMount mount;  // the laser in the keyframe's frame
  };
  std::map<int64_t, std::deque<Held>> held_;  // by object id
  struct Fused {
    Eigen::Matrix2d information = Eigen::Matrix2d::Zero();   // sum of C^-1
    Eigen::Vector2d information_vector = Eigen::Vector2d::Zero();  // sum of C^-1 p
  };
  std::map<int64_t, Fused> fused_;  // by landmark id, in the last keyframe's frame
};

}  // namespace slammtt
