// The last line of defence against a non-finite estimate: every scan ends with a check that
// nothing POSE, MAP or TRACKS would carry is NaN or infinite, and a recovery when something is.
//
// Input validation (feature_validation.h, odometry_plausibility.h, time_base.h) keeps every
// known bad input out, so this should never fire; it is there so that an input nobody thought
// of cannot put a NaN on the bus or leave the filter broken for the rest of the run.
//
// Detection, O(n) per scan: the mean, the diagonal of P, the robot's block and each object's
// 4x4 block (what is published). A NaN anywhere in P reaches the diagonal at the first update
// that uses it. Only when something is found is every row of P scanned (O(n^2)), to name the
// states that are not finite.
// Recovery:
//  - when only objects' states are affected, those objects are removed (the rest of the map,
//    the robot and their correlations are kept; a removed object that is still there is
//    found again as a new object);
//  - when the robot's block is affected, the estimation starts over from the last finite pose
//    with its covariance (the map is lost, the trajectory goes on); the heading drift returns
//    to its prior.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "estimator/slam_state.h"

namespace slammtt {

// True when everything the estimate publishes, the mean and the diagonal of P are finite.
bool PublishedStateIsFinite(const SlamState& state);

// The indices of the states whose mean or whose row of P holds a non-finite value.
std::vector<int> NonFiniteStates(const SlamState& state);

struct RecoveryOutcome {
  bool robot_reset = false;  // started over from the last finite pose
  int objects_removed = 0;
};

// Makes `state` finite as described above. `last_pose` and `last_pose_covariance` are the last
// finite published pose; `heading_drift_variance` the drift's prior variance.
RecoveryOutcome RecoverFiniteState(const Eigen::Vector3d& last_pose,
                                   const Eigen::Matrix3d& last_pose_covariance,
                                   double heading_drift_variance, SlamState* state);

}  // namespace slammtt
