// A small scene for the unit tests of the steps of Algorithm 2 (estimator/*.h, one step each):
// a robot at the origin heading along +x, known to 1 mm and 0.1 mrad, the sensor on the axle,
// objects added where a test wants them and measurements of points taken from the robot.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "estimator/association.h"
#include "estimator/estimator_options.h"
#include "estimator/gating.h"
#include "estimator/observation_predictions.h"
#include "estimator/point_measurement.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"
#include "estimator/step_counts.h"

namespace slammtt::testing {

inline constexpr int64_t kSecond = 1000000;

struct StepScene {
  EstimatorOptions options;
  SlamState state{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
  std::vector<PointMeasurement> measurements;
  StepCounts counts;

  // A static landmark at `position` whose position error is independent of the robot's, of
  // standard deviation sigma_m in x and y. Returns its index.
  int AddLandmark(const Eigen::Vector2d& position, double sigma_m, int64_t id = 0) {
    ObjectRecord record;
    record.id = id != 0 ? id : state.num_objects() + 1;
    record.object_class = ObjectClass::kStatic;
    record.confirmed = true;
    return state.AddObject(position, Eigen::Matrix<double, 2, 3>::Zero(),
                           sigma_m * sigma_m * Eigen::Matrix2d::Identity(), record);
  }
  // An object with velocity states (`object_class` MOVING or UNDECIDED), velocity covariance
  // velocity_sigma_mps^2 I.
  int AddMover(const Eigen::Vector2d& position, double sigma_m, const Eigen::Vector2d& velocity,
               double velocity_sigma_mps, ObjectClass object_class = ObjectClass::kMoving,
               int64_t id = 0) {
    ObjectRecord record;
    record.id = id != 0 ? id : state.num_objects() + 1;
    record.object_class = object_class;
    record.confirmed = true;
    const int k = state.AddObject(position, Eigen::Matrix<double, 2, 3>::Zero(),
                                  sigma_m * sigma_m * Eigen::Matrix2d::Identity(), record);
    state.AddVelocity(k, velocity,
                      velocity_sigma_mps * velocity_sigma_mps * Eigen::Matrix2d::Identity());
    return k;
  }
  // A measurement of the map point `point` from the robot's current pose estimate, with range
  // and bearing standard deviations of 3 cm and 0.01 rad. Returns its index.
  int Measure(const Eigen::Vector2d& point, double range_sigma_m = 0.03,
              double bearing_sigma_rad = 0.01) {
    PointMeasurement z;
    z.range_bearing = PredictRangeBearing(state.robot_pose(), point, options.sensor);
    z.covariance =
        Eigen::Vector2d(range_sigma_m * range_sigma_m, bearing_sigma_rad * bearing_sigma_rad)
            .asDiagonal();
    measurements.push_back(z);
    return static_cast<int>(measurements.size()) - 1;
  }
  std::vector<ObjectPrediction> Predictions() const {
    return PredictObservations(state, options.sensor);
  }
  double Nis(int measurement, int object) const {
    return NormalizedInnovationSquared(measurements[static_cast<size_t>(measurement)],
                                       Predictions()[static_cast<size_t>(object)],
                                       std::numeric_limits<double>::infinity());
  }
  // Every object may update the state.
  std::vector<uint8_t> AllMayUpdate() const {
    return std::vector<uint8_t>(static_cast<size_t>(state.num_objects()), 1);
  }
};

}  // namespace slammtt::testing
