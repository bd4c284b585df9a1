#include "estimator/motion_classifier.h"

#include <algorithm>
#include <cmath>

#include "common/utime.h"

namespace slammtt {

double LargestEigenvalue(const Eigen::Matrix2d& m) {
  const double half_trace = 0.5 * (m(0, 0) + m(1, 1));
  const double det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  return half_trace + std::sqrt(std::max(0.0, half_trace * half_trace - det));
}

bool HasEnoughHitsToMove(const ObjectRecord& record, const MotionClassifierOptions& options) {
  const int min_hits = record.kind == ObjectKind::kPerson
                           ? options.moving_evidence_min_hits
                           : std::max(options.moving_evidence_min_hits,
                                      options.other_moving_evidence_min_hits);
  return record.hits_with_velocity >= min_hits;
}

ClassChange ClassifyMover(const Eigen::Vector2d& position, const Eigen::Matrix2d& position_cov,
                          const Eigen::Vector2d& velocity, const Eigen::Matrix2d& velocity_cov,
                          int64_t utime, const MotionClassifierOptions& options,
                          ObjectRecord* record) {
  const double position_variance = LargestEigenvalue(position_cov);
  const double speed = velocity.norm();
  const Eigen::Matrix2d cov = 0.5 * (velocity_cov + velocity_cov.transpose());
  const double det = cov(0, 0) * cov(1, 1) - cov(0, 1) * cov(1, 0);
  double mahalanobis = 0.0;
  if (det > 0.0) {
    mahalanobis = (cov(1, 1) * velocity(0) * velocity(0) -
                   2.0 * cov(0, 1) * velocity(0) * velocity(1) +
                   cov(0, 0) * velocity(1) * velocity(1)) /
                  det;
  }
  const bool moving = mahalanobis > options.moving_chi2 && speed > options.moving_min_speed_mps;
  if (moving) {
    ++record->moving_evidence_scans;
    RestartStillWindow(position, position_variance, utime, record);
  } else {
    record->moving_evidence_scans = 0;
  }
  if (record->object_class == ObjectClass::kUndecided &&
      record->moving_evidence_scans >= options.moving_confirm_scans &&
      HasEnoughHitsToMove(*record, options)) {
    record->object_class = ObjectClass::kMoving;
    return ClassChange::kBecameMoving;
  }
  if (moving) return ClassChange::kNone;
  // The window's anchor is only as good as the estimate was then: once the position variance
  // has fallen below a fraction of the largest it has been since the window opened (the first
  // estimates of a far object, the end of a coasting), reopen the window here.
  record->still_anchor_variance_m2 = std::max(record->still_anchor_variance_m2, position_variance);
  if (options.still_restart_variance_ratio > 0.0 &&
      position_variance < options.still_restart_variance_ratio * record->still_anchor_variance_m2) {
    RestartStillWindow(position, position_variance, utime, record);
  }
  // The displacement is evidence only when a measurement has just pulled the estimate to where
  // the object is: between measurements the estimate moves with its own velocity, so an object
  // measured once and then unseen (a walker at the edge of detection, seen on one scan in ten,
  // with a velocity estimate near zero) would look still while it walks on.
  const bool measured_now = record->last_seen_utime == utime;
  const double window_s = SecondsBetween(utime, record->still_anchor_utime);
  const double displacement_m = (position - record->still_anchor_m).norm();
  if (measured_now && window_s >= options.still_hold_s &&
      displacement_m <= options.still_max_speed_mps * window_s) {
    return ClassChange::kBecameStatic;
  }
  // The velocity is known to be slow: its confidence region (still_velocity_chi2) lies within
  // moving_min_speed_mps. |v| + sqrt(chi2 lambda_max) bounds the largest speed in the region.
  const double with_velocity_s = SecondsBetween(utime, record->class_change_utime);
  if (options.still_velocity_chi2 > 0.0 && det > 0.0 && with_velocity_s >= options.still_hold_s &&
      speed + std::sqrt(options.still_velocity_chi2 * LargestEigenvalue(cov)) <=
          options.moving_min_speed_mps) {
    return ClassChange::kBecameStatic;
  }
  return ClassChange::kNone;
}

void RestartStillWindow(const Eigen::Vector2d& position, double position_variance_m2,
                        int64_t utime, ObjectRecord* record) {
  record->still_anchor_m = position;
  record->still_anchor_utime = utime;
  record->still_anchor_variance_m2 = position_variance_m2;
}

ClassChange ClassifyLandmark(const Eigen::Vector2d& offset_m, const Eigen::Matrix2d& covariance,
                             const MotionClassifierOptions& options, ObjectRecord* record) {
  constexpr int kWindow = ObjectRecord::kOffsetWindow;
  record->offsets_m[static_cast<size_t>(record->next_offset)] = offset_m;
  record->offset_covariances[static_cast<size_t>(record->next_offset)] = covariance;
  record->next_offset = (record->next_offset + 1) % kWindow;
  record->num_offsets = std::min(kWindow, record->num_offsets + 1);
  if (record->num_offsets < kWindow) return ClassChange::kNone;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_sum = Eigen::Matrix2d::Zero();
  for (int k = 0; k < kWindow; ++k) {
    sum += record->offsets_m[static_cast<size_t>(k)];
    covariance_sum += record->offset_covariances[static_cast<size_t>(k)];
  }
  // mean = sum / k, Cov(mean) = covariance_sum / k^2: mean^T Cov^-1 mean = sum^T covsum^-1 sum.
  const Eigen::Matrix2d c = 0.5 * (covariance_sum + covariance_sum.transpose());
  const double det = c(0, 0) * c(1, 1) - c(0, 1) * c(0, 1);
  if (!(det > 0.0)) return ClassChange::kNone;
  const double statistic =
      (c(1, 1) * sum(0) * sum(0) - 2.0 * c(0, 1) * sum(0) * sum(1) + c(0, 0) * sum(1) * sum(1)) /
      det;
  if (statistic > options.started_moving_chi2) {
    ClearLandmarkEvidence(record);
    return ClassChange::kStartedMoving;
  }
  return ClassChange::kNone;
}

void ClearLandmarkEvidence(ObjectRecord* record) {
  record->num_offsets = 0;
  record->next_offset = 0;
}

void VisitMotionClassifierOptions(OptionVisitor* v, MotionClassifierOptions* c) {
  using R = OptionRange;
  v->Double("moving_chi2", &c->moving_chi2, R::AtLeast(0),
            "velocity significance of moving evidence (13.82: 99.9 %, 2 dof)");
  v->Double("moving_min_speed_mps", &c->moving_min_speed_mps, R::AtLeast(0),
            "least speed of moving evidence");
  v->Double("still_velocity_chi2", &c->still_velocity_chi2, R::AtLeast(0),
            "velocity confidence region of still evidence (0: off)");
  v->Double("still_restart_variance_ratio", &c->still_restart_variance_ratio, R::AtLeast(0),
            "the still window reopens below this share of its largest variance (0: off)");
  v->Int("moving_confirm_scans", &c->moving_confirm_scans, R::Between(1, 1000),
         "consecutive scans of moving evidence that make an object MOVING");
  v->Int("moving_evidence_min_hits", &c->moving_evidence_min_hits, R::Between(0, 1000),
         "measured scans since it got velocity states before an object can become MOVING");
  v->Int("other_moving_evidence_min_hits", &c->other_moving_evidence_min_hits,
         R::Between(0, 1000), "the same for an object that is not of kind person (the larger)");
  v->Double("still_max_speed_mps", &c->still_max_speed_mps, R::AtLeast(0),
            "largest mean speed over the still window of still evidence");
  v->Double("still_hold_s", &c->still_hold_s, R::AtLeast(0), "shortest still window");
  v->Double("started_moving_chi2", &c->started_moving_chi2, R::Above(0),
            "significance of a landmark's mean offset that gives it velocity states");
  v->Double("still_anchor_chi2", &c->still_anchor_chi2, R::AtLeast(0),
            "gate of 'not moved since it got velocity states' when it becomes static (0: off)");
}

}  // namespace slammtt
