// The measurements of one scan that the association levels gave to confirmed static point
// landmarks, by landmark id: what the smoother adds as range-bearing factors (smoother_input.h,
// docs/smoother.md). Read after the classification of the scan (Algorithm 2, line 12), so a
// landmark that turned moving in this scan gives none.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "estimator/association.h"
#include "estimator/point_measurement.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct StaticObservation {
  int64_t landmark_id = 0;
  Eigen::Vector2d range_bearing = Eigen::Vector2d::Zero();  // [m, rad] from the laser (eq. 10)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // R (eq. 14)
};

// Every measurement i of `measurements` assigned to an object j of `state` (the assignment's
// object indices are the state's) that is STATIC, confirmed and of kind OTHER (a standing
// person is no landmark: map_t leaves it out too), and is not itself a person feature; in
// measurement order. Indices outside the state or the measurements are a programming error
// the assignment cannot make (they are skipped, not trusted).
std::vector<StaticObservation> StaticObservations(const std::vector<PointMeasurement>& measurements,
                                                  const Assignment& assignment,
                                                  const SlamState& state);

}  // namespace slammtt
