#include "estimator/classification.h"

#include <Eigen/LU>
#include <limits>

#include "estimator/motion_classifier.h"
#include "estimator/range_bearing_model.h"

namespace slammtt {
namespace {

Eigen::Matrix2d PositionCovariance(const SlamState& state, int j) {
  const int p = state.object(j).position_index;
  return state.covariance().block<2, 2>(p, p);
}

// An object with velocity states: ClassifyMover, and the state follows a change to STATIC.
void ClassifyObjectWithVelocity(int j, int64_t utime, const EstimatorOptions& options,
                                SlamState* state, StepCounts* counts) {
  const SlamState& now = *state;
  const int v = now.object(j).velocity_index;
  const Eigen::Matrix2d velocity_cov = now.covariance().block<2, 2>(v, v);
  const ClassChange change =
      ClassifyMover(now.position(j), PositionCovariance(now, j), now.velocity(j), velocity_cov,
                    utime, options.classifier, &state->object(j).record);
  if (change == ClassChange::kBecameMoving) {
    state->RemoveAnchor(j);  // it moved: the stationary hypothesis is given up
    state->object(j).record.class_change_utime = utime;
    ++counts->became_moving;
  } else if (change == ClassChange::kBecameStatic) {
    // Static since its anchor, unless the displacement says otherwise (a mover that stopped).
    state->ConditionOnAnchorAndRemoveIt(j, options.classifier.still_anchor_chi2);
    state->RemoveVelocityAssumingZero(j);
    ObjectRecord& r = state->object(j).record;
    r.object_class = ObjectClass::kStatic;
    r.class_change_utime = utime;
    r.moving_evidence_scans = 0;
    ClearLandmarkEvidence(&r);
    ++counts->became_static;
  }
}

// A static landmark with a measurement `z` speaking about it: ClassifyLandmark on the measured
// point's offset, and velocity states back when it started moving.
void ClassifyLandmarkWithMeasurement(int j, const PointMeasurement& z,
                                     const ObjectPrediction& prediction, int64_t utime,
                                     const EstimatorOptions& options, SlamState* state,
                                     StepCounts* counts) {
  const SlamState& now = *state;
  const Eigen::Vector2d measured =
      PointFromRangeBearing(now.robot_pose(), z.range_bearing, options.sensor);
  const Eigen::Matrix2d to_map = prediction.jacobian_position.inverse();
  const Eigen::Matrix2d covariance = to_map * (prediction.hph + z.covariance) * to_map.transpose();
  if (ClassifyLandmark(measured - now.position(j), covariance, options.classifier,
                       &state->object(j).record) != ClassChange::kStartedMoving) {
    return;
  }
  const double sigma = options.new_object_velocity_sigma_mps;
  state->AddVelocity(j, Eigen::Vector2d::Zero(), sigma * sigma * Eigen::Matrix2d::Identity());
  if (options.classifier.still_anchor_chi2 > 0.0) state->AddStationaryAnchor(j);
  ObjectRecord& r = state->object(j).record;
  r.object_class = ObjectClass::kUndecided;
  r.class_change_utime = utime;
  r.moving_evidence_scans = 0;
  // This scan's measurement counts when it was the landmark's own (RecordHit came first).
  r.hits_with_velocity = r.last_seen_utime == utime ? 1 : 0;
  RestartStillWindow(now.position(j), LargestEigenvalue(PositionCovariance(now, j)), utime, &r);
  ++counts->started_moving;
}

}  // namespace

std::vector<int> LandmarkMeasurements(const std::vector<Candidate>& gated,
                                      const EstimatorOptions& options, const SlamState& state,
                                      const Assignment& assignment) {
  const size_t num_objects = static_cast<size_t>(assignment.num_objects());
  std::vector<int> measurement(num_objects, -1);
  std::vector<double> nis(num_objects, std::numeric_limits<double>::infinity());
  for (const Candidate& c : gated) {
    if (state.object(c.object).has_velocity()) continue;
    const int assigned = assignment.ObjectOf(c.measurement);
    const size_t j = static_cast<size_t>(c.object);
    if (assigned == c.object) {
      measurement[j] = c.measurement;
      nis[j] = -1.0;  // its own measurement wins
    } else if (assigned < 0 && assignment.ObjectFree(c.object) &&
               c.nis < options.new_object_gate_dn_chi2 && c.nis < nis[j]) {
      measurement[j] = c.measurement;
      nis[j] = c.nis;
    }
  }
  return measurement;
}

void ClassifyObjects(const ScanAssociation& scan, const std::vector<Candidate>& gated,
                     const EstimatorOptions& options,
                     const std::vector<ObjectPrediction>& after_updates,
                     const Assignment& assignment, SlamState* state, StepCounts* counts) {
  if (options.mode == AssociationMode::kStaticNearestNeighbour) return;
  // Chosen before any class changes, judged at the state after the updates.
  const std::vector<int> landmark_measurement =
      LandmarkMeasurements(gated, options, *state, assignment);
  for (int j = 0; j < assignment.num_objects(); ++j) {
    if (state->object(j).has_velocity()) {
      ClassifyObjectWithVelocity(j, scan.utime, options, state, counts);
      continue;
    }
    const int i = landmark_measurement[static_cast<size_t>(j)];
    const ObjectPrediction& prediction = after_updates[static_cast<size_t>(j)];
    if (i < 0 || !prediction.valid) continue;
    ClassifyLandmarkWithMeasurement(j, scan.measurements[static_cast<size_t>(i)], prediction,
                                    scan.utime, options, state, counts);
  }
}

}  // namespace slammtt
