// For the filter-only tests: a landmark enters the state where a measurement places it, with
// the inverse of eq. 10 and its Jacobians (the cross-covariance with the robot that new_objects.h
// gives a new object).
#pragma once

#include <Eigen/Core>

#include "estimator/ekf_update.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Returns the new object's index in `state`.
inline int AddLandmarkFromMeasurement(const PointMeasurement& z, const SensorMount& mount,
                                      const ObjectRecord& record, SlamState* state) {
  Eigen::Matrix<double, 2, 3> g_robot;
  Eigen::Matrix2d g_measurement;
  const Eigen::Vector2d point = PointFromRangeBearing(state->robot_pose(), z.range_bearing, mount,
                                                      &g_robot, &g_measurement);
  return state->AddObject(point, g_robot, g_measurement * z.covariance * g_measurement.transpose(),
                          record);
}

}  // namespace slammtt
