// The measurements of one scan that the association levels gave to point landmarks, by
// landmark id: what the smoother adds as range-bearing factors (smoother_input.h,
// docs/smoother.md). Confirmed static landmarks, and, marked tentative, objects that may become
// one (undecided or not yet confirmed): the smoother holds those until the object is a confirmed
// static landmark, so that a landmark keeps the sightings from before its classification (the
// filter had them too; without them the landmark would be placed where the robot's drifted pose
// puts it when it is confirmed). Read after the classification of the scan (Algorithm 2, line
// 12), so a landmark that turned moving in this scan gives none.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "estimator/association.h"
#include "estimator/point_measurement.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Whether an object of this class and kind may be a point landmark (now or once classified):
// not MOVING, and of kind OTHER (a standing person is no landmark: map_t leaves it out too).
inline bool MayBePointLandmark(ObjectClass object_class, ObjectKind kind) {
  return object_class != ObjectClass::kMoving && kind == ObjectKind::kOther;
}

struct StaticObservation {
  int64_t landmark_id = 0;
  Eigen::Vector2d range_bearing = Eigen::Vector2d::Zero();  // [m, rad] from the laser (eq. 10)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // R (eq. 14)
  bool tentative = false;  // the object is not (yet) a confirmed static landmark
};

// Every measurement i of `measurements` assigned to an object j of `state` (the assignment's
// object indices are the state's) that is not MOVING, of kind OTHER (a standing person is no
// landmark: map_t leaves it out too), and is not itself a person feature; in measurement order;
// tentative unless the object is STATIC and confirmed. Indices outside the state or the
// measurements are a programming error the assignment cannot make (skipped, not trusted).
std::vector<StaticObservation> StaticObservations(const std::vector<PointMeasurement>& measurements,
                                                  const Assignment& assignment,
                                                  const SlamState& state);

}  // namespace slammtt
