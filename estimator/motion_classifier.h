// Static / moving classification of objects with no prior knowledge (paper Algorithm 2,
// line 12), from the estimated velocity and its uncertainty, with hysteresis, in both
// directions.
//
// Objects with velocity states (UNDECIDED or MOVING) are judged on their velocity estimate v
// with covariance P_v at every scan:
//   "moving" evidence: v^T P_v^-1 v > moving_chi2 (the velocity differs significantly from
//                      zero) and |v| > moving_min_speed_mps (and not a crawl);
//   "still" evidence:  |v| < still_max_speed_mps and the largest velocity standard deviation
//                      is below still_max_sigma_mps (we know it well enough to say it is slow).
// UNDECIDED -> MOVING after moving_confirm_scans consecutive "moving" scans.
// UNDECIDED or MOVING -> STATIC after still_hold_s of uninterrupted "still" evidence; the
// estimator then conditions the state on v = 0 and removes the velocity states
// (SlamState::RemoveVelocityAssumingZero).
// A STATIC landmark has no velocity to judge; it is judged on its measurements instead: a scan
// in which its associated measurement has a normalized innovation squared above
// started_moving_nis, or in which it got no measurement while an unassociated measurement lies
// within the new-object gate of it, is "it moved" evidence; a well-fitting measurement resets
// it. After started_moving_scans consecutive such scans the landmark gets velocity states
// again (zero mean, prior covariance) and becomes UNDECIDED, so the velocity test above
// decides from then on.
#pragma once

#include <Eigen/Core>

#include "estimator/slam_state.h"

namespace slammtt {

struct MotionClassifierOptions {
  double moving_chi2 = 9.21;              // 99 % for 2 dof
  double moving_min_speed_mps = 0.3;
  int moving_confirm_scans = 2;
  double still_max_speed_mps = 0.2;
  double still_max_sigma_mps = 0.25;
  double still_hold_s = 2.0;
  double started_moving_nis = 9.21;
  int started_moving_scans = 2;
};

enum class ClassChange {
  kNone,
  kBecameMoving,       // UNDECIDED -> MOVING (no state change)
  kBecameStatic,       // remove the velocity states assuming v = 0
  kStartedMoving,      // STATIC -> UNDECIDED: add velocity states
};

// What a scan says about a static landmark's measurements.
enum class StaticObservation {
  kFits,          // associated, NIS <= started_moving_nis
  kMisfits,       // associated with a large NIS, or an unassociated measurement near it
  kNothing,       // not observed (occluded, out of view): no evidence either way
};

// Judges an object with velocity states and updates its evidence; dt_s is the time since the
// previous scan. Returns the class change to apply (the record's object_class is updated for
// kBecameMoving; the caller updates it for the other changes once the state is changed).
ClassChange ClassifyMover(const Eigen::Vector2d& velocity, const Eigen::Matrix2d& velocity_cov,
                          double dt_s, const MotionClassifierOptions& options,
                          ObjectRecord* record);

// Judges a static landmark from what this scan saw of it.
ClassChange ClassifyLandmark(StaticObservation observation,
                             const MotionClassifierOptions& options, ObjectRecord* record);

}  // namespace slammtt
