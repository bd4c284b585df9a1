#include "estimator/ekf_update.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "estimator/angle.h"

namespace slammtt {
bool ApplyLinearisedGroup(const std::vector<LinearisedObservation>& group, SlamState* state) {
  const int n = state->dim();
  const int k = static_cast<int>(group.size());
  auto cov = state->covariance();
  // W = P H^T (n x 2k), from the robot pose's and the object's columns only (H is zero on the
  // heading drift state, index 3: a range and bearing do not depend on it; its row of W, and so
  // its update, comes through its correlation with the pose).
  Eigen::MatrixXd w(n, 2 * k);
  for (int t = 0; t < k; ++t) {
    const LinearisedObservation& o = group[static_cast<size_t>(t)];
    w.middleCols<2>(2 * t).noalias() = cov.leftCols<3>() * o.h_robot.transpose();
    w.middleCols<2>(2 * t).noalias() += cov.middleCols<2>(o.position_index) * o.h_position.transpose();
  }
  // S = H W + R.
  Eigen::MatrixXd s(2 * k, 2 * k);
  for (int t = 0; t < k; ++t) {
    const LinearisedObservation& o = group[static_cast<size_t>(t)];
    s.middleRows<2>(2 * t).noalias() = o.h_robot * w.topRows<3>();
    s.middleRows<2>(2 * t).noalias() += o.h_position * w.middleRows<2>(o.position_index);
    s.block<2, 2>(2 * t, 2 * t) += o.r;
  }
  const Eigen::MatrixXd s_symmetric = 0.5 * (s + s.transpose());
  Eigen::LLT<Eigen::MatrixXd> llt(s_symmetric);
  if (llt.info() != Eigen::Success) return false;
  Eigen::VectorXd innovation(2 * k);
  for (int t = 0; t < k; ++t) innovation.segment<2>(2 * t) = group[static_cast<size_t>(t)].innovation;
  // V^T = L^-1 W^T (2k x n).
  Eigen::MatrixXd v_transposed = w.transpose();
  llt.matrixL().solveInPlace(v_transposed);
  const Eigen::VectorXd whitened = llt.matrixL().solve(innovation);
  auto mean = state->mean();
  mean.noalias() += v_transposed.transpose() * whitened;
  mean(2) = WrapAngle(mean(2));
  state->SubtractSymmetricProduct(v_transposed);
  return true;
}

UpdateStats ApplyObservations(const std::vector<ObjectObservation>& observations,
                              const SensorMount& mount, double gate_chi2, int group_size,
                              SlamState* state) {
  UpdateStats stats;
  const size_t group = static_cast<size_t>(std::max(1, group_size));
  std::vector<LinearisedObservation> linearised;
  for (size_t begin = 0; begin < observations.size(); begin += group) {
    const size_t end = std::min(observations.size(), begin + group);
    linearised.clear();
    const Eigen::Vector3d robot = state->robot_pose();
    const auto cov = state->covariance();
    for (size_t i = begin; i < end; ++i) {
      const ObjectObservation& observation = observations[i];
      const StateObject& object = state->object(observation.object);
      const Eigen::Vector2d position = state->position(observation.object);
      LinearisedObservation l;
      l.position_index = object.position_index;
      const Eigen::Vector2d sensor = SensorPosition(robot, mount);
      if ((position - sensor).norm() < kMinPredictedRange_m) {
        ++stats.failed;
        continue;
      }
      const Eigen::Vector2d predicted =
          PredictRangeBearing(robot, position, mount, &l.h_robot, &l.h_position);
      if (state->first_estimate_jacobians() && state->has_predicted_pose() &&
          !object.has_velocity()) {
        // First-estimate Jacobians (slam_state.h): a static landmark's, at the pose predicted
        // for this scan and the landmark's first estimate; the innovation at the current
        // estimates. (An object with velocity states keeps the standard Jacobians: its first
        // estimates would have to follow it by the model from its birth, at zero velocity.)
        PredictRangeBearing(state->predicted_pose(), object.first_estimate_m, mount, &l.h_robot,
                            &l.h_position);
      }
      l.innovation = observation.measurement.range_bearing - predicted;
      l.innovation(1) = WrapAngle(l.innovation(1));
      l.r = observation.measurement.covariance;
      if (std::isfinite(gate_chi2)) {
        const int p = l.position_index;
        Eigen::Matrix2d s = l.h_robot * cov.topLeftCorner<3, 3>() * l.h_robot.transpose() +
                            l.h_position * cov.block<2, 2>(p, p) * l.h_position.transpose() + l.r;
        const Eigen::Matrix2d cross = l.h_robot * cov.block<3, 2>(0, p) * l.h_position.transpose();
        s += cross + cross.transpose();
        const double nis = l.innovation.dot(s.ldlt().solve(l.innovation));
        if (!(nis < gate_chi2)) {
          ++stats.gated_out;
          continue;
        }
      }
      linearised.push_back(l);
    }
    if (linearised.empty()) continue;
    if (ApplyLinearisedGroup(linearised, state)) {
      stats.applied += static_cast<int>(linearised.size());
    } else {
      stats.failed += static_cast<int>(linearised.size());
    }
  }
  return stats;
}

}  // namespace slammtt
