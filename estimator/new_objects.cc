#include "estimator/new_objects.h"

#include <limits>

#include "estimator/motion_classifier.h"
#include "estimator/people.h"
#include "estimator/range_bearing_model.h"
#include "estimator/track_management.h"

namespace slammtt {

namespace {

// A measurement placed in the map from the robot's pose (the inverse of eq. 10 with the mount,
// eq. 11): the point, its Jacobian with respect to the robot's pose and the measurement's
// covariance carried into the map frame, as a new object starts.
struct PlacedMeasurement {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 2, 3> jacobian_robot = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

PlacedMeasurement Place(const PointMeasurement& z, const EstimatorOptions& options,
                        const SlamState& state) {
  PlacedMeasurement placed;
  Eigen::Matrix2d jacobian_measurement;
  placed.position = PointFromRangeBearing(state.robot_pose(), z.range_bearing, options.sensor,
                                          &placed.jacobian_robot, &jacobian_measurement);
  placed.covariance = jacobian_measurement * z.covariance * jacobian_measurement.transpose();
  return placed;
}

}  // namespace

std::vector<StaticObservation> AddNewObjects(const ScanAssociation& scan,
                                             const std::vector<double>& nearest_nis,
                                             const std::vector<int64_t>& continues_id,
                                             const EstimatorOptions& options,
                                             const Assignment& assignment, int64_t* next_id,
                                             SlamState* state, StepCounts* counts) {
  std::vector<StaticObservation> first_sightings;
  const bool static_world = options.mode == AssociationMode::kStaticNearestNeighbour;
  for (int i = 0; i < assignment.num_measurements(); ++i) {
    if (!assignment.MeasurementFree(i) ||
        nearest_nis[static_cast<size_t>(i)] < options.new_object_gate_dn_chi2) {
      continue;
    }
    if (state->num_objects() >= options.max_objects) {
      ++counts->objects_refused;
      continue;
    }
    const PointMeasurement& z = scan.measurements[static_cast<size_t>(i)];
    const PlacedMeasurement placed = Place(z, options, *state);
    const Eigen::Vector2d& position = placed.position;
    // A person feature this close to a person track is that person (people.h).
    if (!static_world && z.person && TooCloseToAPerson(position, options.people, *state)) {
      ++counts->person_births_joined;
      continue;
    }
    ObjectRecord record = NewObjectRecord(
        (*next_id)++, scan.utime, static_world ? ObjectClass::kStatic : ObjectClass::kUndecided);
    RestartStillWindow(position, std::numeric_limits<double>::infinity(), scan.utime, &record);
    record.confirmed = static_world;
    record.last_seen_m = position;
    record.continues_id = continues_id[static_cast<size_t>(i)];
    record.person_hits = z.person ? 1 : 0;
    record.pair_hits = z.person && z.pair_confidence > 0.0 ? 1 : 0;
    record.kind = KindOfRecord(record);
    record.birth_pair_confidence =
        z.person && !BesideAPersonOrMover(position, options.people, *state) ? z.pair_confidence
                                                                            : 0.0;
    const int k = state->AddObject(position, placed.jacobian_robot, placed.covariance, record);
    if (!static_world) {
      const double sigma = options.new_object_velocity_sigma_mps;
      state->AddVelocity(k, Eigen::Vector2d::Zero(), sigma * sigma * Eigen::Matrix2d::Identity());
      if (options.classifier.still_anchor_chi2 > 0.0) state->AddStationaryAnchor(k);
    }
    if (!z.person && MayBePointLandmark(record.object_class, record.kind)) {
      first_sightings.push_back(
          StaticObservation{record.id, z.range_bearing, z.covariance, !record.confirmed});
    }
    ++counts->new_objects;
  }
  return first_sightings;
}

int RestartObjectsBesideBirths(const std::vector<int>& objects, const ScanAssociation& scan,
                               const Assignment& assignment, const EstimatorOptions& options,
                               SlamState* state) {
  int restarted = 0;
  for (const int k : objects) {
    ObjectRecord& record = state->object(k).record;
    const int own = assignment.MeasurementOf(k);
    if (record.object_class != ObjectClass::kUndecided || own < 0) continue;
    record.moving_evidence_scans = 0;
    ++restarted;
    if (!options.new_object_beside_claimed_restarts_state) continue;
    const PlacedMeasurement placed =
        Place(scan.measurements[static_cast<size_t>(own)], options, *state);
    const Eigen::Vector2d& position = placed.position;
    const double sigma = options.new_object_velocity_sigma_mps;
    state->RestartObject(k, position, placed.jacobian_robot, placed.covariance,
                         sigma * sigma * Eigen::Matrix2d::Identity());
    // Its velocity (and still window) start at this scan, with this scan's measurement.
    record.hits_with_velocity = 1;
    record.last_seen_m = position;
    RestartStillWindow(position, std::numeric_limits<double>::infinity(), scan.utime, &record);
  }
  return restarted;
}

}  // namespace slammtt
