// One point feature as the estimator uses it: range and bearing from the sensor (paper eq. 10)
// with its covariance R (eq. 14).
#pragma once

#include <Eigen/Core>

namespace slammtt {

struct PointMeasurement {
  Eigen::Vector2d range_bearing = Eigen::Vector2d::Zero();  // [m, rad], bearing in (-pi, pi]
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // R over (range, bearing)
  bool person = false;  // the centre of a person feature (two legs, or one with a larger R)
  double pair_confidence = 0.0;  // two legs: perception's confidence in [0, 1]; else 0
};

}  // namespace slammtt
