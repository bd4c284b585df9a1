#include "estimator/state_recovery.h"

#include <cmath>

namespace slammtt {

bool PublishedStateIsFinite(const SlamState& state) {
  if (!state.mean().allFinite() || !state.covariance().diagonal().allFinite()) return false;
  if (!state.covariance().topLeftCorner<SlamState::kRobotDim, SlamState::kRobotDim>()
           .allFinite()) {
    return false;
  }
  for (int k = 0; k < state.num_objects(); ++k) {
    if (!state.ObjectCovariance(k).allFinite()) return false;
  }
  return true;
}

std::vector<int> NonFiniteStates(const SlamState& state) {
  std::vector<int> bad;
  const auto mean = state.mean();
  const auto cov = state.covariance();
  for (int i = 0; i < state.dim(); ++i) {
    if (!std::isfinite(mean(i)) || !cov.col(i).allFinite()) bad.push_back(i);
  }
  return bad;
}

RecoveryOutcome RecoverFiniteState(const Eigen::Vector3d& last_pose,
                                   const Eigen::Matrix3d& last_pose_covariance,
                                   double heading_drift_variance, SlamState* state) {
  RecoveryOutcome outcome;
  const std::vector<int> bad = NonFiniteStates(*state);
  if (bad.empty()) return outcome;
  if (bad.front() < SlamState::kRobotDim) {
    const bool first_estimates = state->first_estimate_jacobians();
    *state = SlamState(last_pose, last_pose_covariance, heading_drift_variance);
    state->set_first_estimate_jacobians(first_estimates);
    outcome.robot_reset = true;
    return outcome;
  }
  std::vector<int> objects;
  for (int k = 0; k < state->num_objects(); ++k) {
    const StateObject& o = state->object(k);
    for (int i : bad) {
      if (i == o.position_index || i == o.position_index + 1 ||
          (o.has_velocity() && (i == o.velocity_index || i == o.velocity_index + 1)) ||
          (o.has_anchor() && (i == o.anchor_index || i == o.anchor_index + 1))) {
        objects.push_back(k);
        break;
      }
    }
  }
  state->RemoveObjects(objects);
  outcome.objects_removed = static_cast<int>(objects.size());
  return outcome;
}

}  // namespace slammtt
