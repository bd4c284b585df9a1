// EKF measurement update with range-bearing observations of objects (paper eq. 22).
//
// Observations are applied in groups: each group is one batch update with the stacked
// Jacobian of its observations (eq. 22's "augmented Jacobian of all measurements"), the groups
// one after the other, each linearised at the state the previous one left. For a linear model
// this is exactly the batch update; it bounds the cost of the innovation solve to
// O(n * group^2) per group instead of O(n * k^2) for k observations at once, while the
// covariance downdate stays a cache-friendly rank-2*group product.
//
// The covariance is updated in the factored symmetric form
//   S = H P H^T + R = L L^T,  V = P H^T L^-T,  P+ = P - V V^T,  x+ = x + V L^-1 (z - h(x)),
// the Cholesky form of Bailey's EKF-SLAM (paper ref. [27]; Bailey's toolbox KF_cholesky_update):
// algebraically eq. 22, but symmetric by construction (only one triangle is computed and
// mirrored) and without forming the gain K, which keeps P positive semi-definite over long
// runs (checked by the soak test). H has non-zeros only on the robot and on the observed
// object's position, so P H^T reads 5 columns of P per observation.
#pragma once

#include <vector>

#include "estimator/point_measurement.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct ObjectObservation {
  int object = -1;  // index into SlamState::objects()
  PointMeasurement measurement;
};

struct UpdateStats {
  int applied = 0;    // observations that updated the state
  int gated_out = 0;  // rejected: normalized innovation squared above the gate
  int failed = 0;     // numerically unusable (object at the sensor, S not positive definite)
};

// One observation linearised at the current state: h(x) depends on the robot pose (H_r, 2x3)
// and on one slot of two states at position_index (an object's position, or a line landmark's
// (rho, alpha): line_landmarks.h) (H_s, 2x2).
struct LinearisedObservation {
  int position_index = -1;
  Eigen::Vector2d innovation = Eigen::Vector2d::Zero();  // z - h(x), angles wrapped
  Eigen::Matrix<double, 2, 3> h_robot = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix2d h_position = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d r = Eigen::Matrix2d::Identity();
};

// One batch update (eq. 22) of already linearised observations, in the factored form above;
// the robot heading is wrapped after it. False (state unchanged) when S is not positive
// definite.
bool ApplyLinearisedGroup(const std::vector<LinearisedObservation>& group, SlamState* state);

// Applies `observations` (each object at most once is the normal use). An observation whose
// normalized innovation squared against the state at the start of its group is >= gate_chi2
// is skipped (pass infinity to disable). group_size >= 1.
UpdateStats ApplyObservations(const std::vector<ObjectObservation>& observations,
                              const SensorMount& mount, double gate_chi2, int group_size,
                              SlamState* state);

}  // namespace slammtt
