#include "estimator/motion_classifier.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

ClassChange ClassifyMover(const Eigen::Vector2d& velocity, const Eigen::Matrix2d& velocity_cov,
                          double dt_s, const MotionClassifierOptions& options,
                          ObjectRecord* record) {
  const double speed = velocity.norm();
  const Eigen::Matrix2d cov = 0.5 * (velocity_cov + velocity_cov.transpose());
  const double det = cov(0, 0) * cov(1, 1) - cov(0, 1) * cov(1, 0);
  double mahalanobis = 0.0;
  if (det > 0.0) {
    mahalanobis = (cov(1, 1) * velocity(0) * velocity(0) - 2.0 * cov(0, 1) * velocity(0) * velocity(1) +
                   cov(0, 0) * velocity(1) * velocity(1)) /
                  det;
  }
  // Largest eigenvalue of a symmetric 2x2.
  const double half_trace = 0.5 * (cov(0, 0) + cov(1, 1));
  const double half_gap = std::sqrt(0.25 * (cov(0, 0) - cov(1, 1)) * (cov(0, 0) - cov(1, 1)) +
                                    cov(0, 1) * cov(0, 1));
  const double largest_sigma = std::sqrt(std::max(0.0, half_trace + half_gap));

  const bool moving = mahalanobis > options.moving_chi2 && speed > options.moving_min_speed_mps;
  const bool still =
      speed < options.still_max_speed_mps && largest_sigma < options.still_max_sigma_mps;

  record->moving_evidence_scans = moving ? record->moving_evidence_scans + 1 : 0;
  record->static_evidence_s = still ? record->static_evidence_s + dt_s : 0.0;

  if (record->object_class == ObjectClass::kUndecided &&
      record->moving_evidence_scans >= options.moving_confirm_scans) {
    record->object_class = ObjectClass::kMoving;
    return ClassChange::kBecameMoving;
  }
  if (record->static_evidence_s >= options.still_hold_s) return ClassChange::kBecameStatic;
  return ClassChange::kNone;
}

ClassChange ClassifyLandmark(StaticObservation observation,
                             const MotionClassifierOptions& options, ObjectRecord* record) {
  switch (observation) {
    case StaticObservation::kFits:
      record->motion_evidence_scans = 0;
      break;
    case StaticObservation::kMisfits:
      ++record->motion_evidence_scans;
      break;
    case StaticObservation::kNothing:
      break;
  }
  if (record->motion_evidence_scans >= options.started_moving_scans) {
    record->motion_evidence_scans = 0;
    return ClassChange::kStartedMoving;
  }
  return ClassChange::kNone;
}

}  // namespace slammtt
