// Static / moving classification of objects with no prior knowledge (paper Algorithm 2,
// line 12), from the estimated velocity and its uncertainty, with hysteresis, in both
// directions.
//
// Objects with velocity states (UNDECIDED or MOVING) are judged at every scan:
//   "moving" evidence: v^T P_v^-1 v > moving_chi2 (the velocity estimate differs significantly
//                      from zero) and |v| > moving_min_speed_mps;
//   "still" evidence:  since the last moving evidence (or since the object got its velocity
//                      states), at least still_hold_s have passed and the position estimate
//                      has moved by at most still_max_speed_mps times that time, judged only
//                      at a scan in which the object got a measurement (record->last_seen_utime
//                      == utime: between measurements the estimate moves with its own velocity
//                      estimate, which says nothing about the object).
// The still test looks at the displacement over a window that grows, not at the instantaneous
// velocity estimate: with the process noise movers need (sigma_Q), a static object's velocity
// estimate keeps a standard deviation of about 0.2 m/s at the paper's sensor noise, while the
// mean velocity over T seconds is known to about sigma_position * sqrt(2) / T.
// UNDECIDED -> MOVING after moving_confirm_scans consecutive "moving" scans, once the object
// has had moving_evidence_min_hits measured scans since it got its velocity states
// (other_moving_evidence_min_hits for an object that is not of kind PERSON).
// UNDECIDED or MOVING -> STATIC on "still" evidence; the estimator then conditions the state on
// v = 0 and removes the velocity states (SlamState::RemoveVelocityAssumingZero).
// A STATIC landmark has no velocity to judge; it is judged on its measurements instead. Each
// scan that has a measurement of it (its associated one, or else an unassociated measurement
// inside the new-object gate of it: most likely the landmark, moved) adds the offset d of the
// measured point from the landmark in the map frame, with covariance C = H_p^-1 S H_p^-T (the
// innovation mapped to the map frame). Over the last k = ObjectRecord::kOffsetWindow offsets,
// the mean offset d_mean has covariance C_mean = (sum C) / k^2 if the landmark is where the
// map says (EKF innovations are white), and
//   d_mean^T C_mean^-1 d_mean > started_moving_chi2
// says it moved: a steady drift accumulates in the mean while noise averages out, so a person
// walking off is caught before leaving the association gate. The landmark then gets velocity
// states again (zero mean, prior covariance) and becomes UNDECIDED, so the velocity test above
// decides from then on.
#pragma once

#include <Eigen/Core>

#include "common/options_schema.h"

#include "estimator/slam_state.h"

namespace slammtt {

struct MotionClassifierOptions {
  double moving_chi2 = 13.82;             // 99.9 % for 2 dof
  double moving_min_speed_mps = 0.3;
  // > 0: "still" evidence also when the velocity's confidence region at this chi-square
  // (2 dof) lies within speed moving_min_speed_mps.
  double still_velocity_chi2 = 5.99;
  // > 0: the still window reopens at the current estimate whenever the position variance has
  // fallen below this fraction of the largest it has been since the window opened.
  double still_restart_variance_ratio = 0.5;
  int moving_confirm_scans = 2;
  // An UNDECIDED object becomes MOVING only after at least this many scans with a measurement
  // since it got its velocity states (ObjectRecord::hits_with_velocity). A velocity estimated
  // from two sightings of a cluster that comes and goes (a wall edge seen through dropouts, a
  // chair leg at the edge of detection, a mixed pixel) is the difference of two noisy points
  // taken a few scans apart, not evidence of motion: with a third measurement the estimate has
  // to predict where the object is, which a flickering cluster's does not. 0 or 1: no minimum.
  int moving_evidence_min_hits = 0;
  // The same minimum for an object that is not of kind PERSON (people.h), taken with
  // moving_evidence_min_hits (the larger counts). A person is recognised by its shape (two legs
  // paired) and needs no more evidence of motion than its velocity; anything else is found
  // only by its motion, and the clusters that move without moving (a piece of a far wall seen
  // through dropouts whose fitted centre slides along it, a chair's occlusion edge, a cluster
  // seen once and again a second later a metre away) keep a significant velocity for a few
  // scans. With 8 (0.8 s at 10 Hz) and tracks' other_tentative_prune_unconfirmable, office and
  // corridor seeds 1-20 meet "at most 1 non-person mover per minute" with and without
  // ODOMETRY and people MOTA improves (docs/estimator.md, "Classification"); off (0) by
  // default because the real recordings' person tracks get worse: negative_2 25.9 -> 38.4
  // person identities per minute, leg_tracker_demo 18.1 -> 19.5 (their floors).
  int other_moving_evidence_min_hits = 0;
  double still_max_speed_mps = 0.15;
  double still_hold_s = 1.5;
  double started_moving_chi2 = 23.0;      // 1e-5 false alarms per scan and landmark (2 dof)
  // > 0: an object that gets velocity states keeps a stationary anchor (a stochastically cloned
  // copy of its position then: SlamState::AddStationaryAnchor). When it becomes STATIC, the
  // state is conditioned on its not having moved since, if that displacement's NIS is below
  // this chi-square (2 dof; 13.82, 99.9 %, as moving_chi2), so that what its measurements said
  // while it was undecided (and the robot's motion then) is not lost to its velocity states.
  // 0: off (the conditioning on v = 0 alone). With the local window it once made duplicates of
  // re-entered landmarks STATIC (fixed by scan_gating.h: BlockBirthsInsideHeldBackGates;
  // docs/estimator.md, "Stationary anchor"). Off by default: on the 1000-landmark large loop it
  // still costs the smoothed map (seeds 3 / 6 smoothed static recall 0.990 / 0.982 off against
  // 0.752 / 0.380 on), more than it gives s1-crossing (17 against 16 of 30 seeds).
  double still_anchor_chi2 = 0.0;
};

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `classifier`).
void VisitMotionClassifierOptions(OptionVisitor* visitor, MotionClassifierOptions* options);

enum class ClassChange {
  kNone,
  kBecameMoving,       // UNDECIDED -> MOVING (no state change)
  kBecameStatic,       // remove the velocity states assuming v = 0
  kStartedMoving,      // STATIC -> UNDECIDED: add velocity states
};

// Whether the object has had moving_evidence_min_hits (other_moving_evidence_min_hits, if
// larger, for an object not of kind PERSON) measured scans since it got its velocity states (it
// may become MOVING).
bool HasEnoughHitsToMove(const ObjectRecord& record, const MotionClassifierOptions& options);

// Judges an object with velocity states at utime and updates its evidence. Returns the class
// change to apply (the record's object_class is updated for kBecameMoving; the caller updates
// it for kBecameStatic once the state is changed).
ClassChange ClassifyMover(const Eigen::Vector2d& position, const Eigen::Matrix2d& position_cov,
                          const Eigen::Vector2d& velocity, const Eigen::Matrix2d& velocity_cov,
                          int64_t utime, const MotionClassifierOptions& options,
                          ObjectRecord* record);

// Opens a new "still" window at the object's current position (creation, new velocity states).
// position_variance_m2: largest eigenvalue of its position covariance (+infinity: unknown, the
// window restarts at the next judgement).
void RestartStillWindow(const Eigen::Vector2d& position, double position_variance_m2,
                        int64_t utime, ObjectRecord* record);

// Largest eigenvalue of a symmetric 2x2 matrix.
double LargestEigenvalue(const Eigen::Matrix2d& symmetric);

// Adds one offset of a measured point from a static landmark (map frame, with covariance) and
// judges the window. Returns kStartedMoving (and clears the window) when the landmark moved.
ClassChange ClassifyLandmark(const Eigen::Vector2d& offset_m, const Eigen::Matrix2d& covariance,
                             const MotionClassifierOptions& options, ObjectRecord* record);

// Forgets a landmark's offsets (after a class change).
void ClearLandmarkEvidence(ObjectRecord* record);

}  // namespace slammtt
