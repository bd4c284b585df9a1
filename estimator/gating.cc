#include "estimator/gating.h"

#include <cmath>
#include <limits>

#include "estimator/angle.h"

namespace slammtt {

std::vector<ObjectPrediction> PredictObservations(const SlamState& state,
                                                  const SensorMount& mount) {
  std::vector<ObjectPrediction> predictions(static_cast<size_t>(state.num_objects()));
  const Eigen::Vector3d robot = state.robot_pose();
  const Eigen::Vector2d sensor = SensorPosition(robot, mount);
  const auto cov = state.covariance();
  const Eigen::Matrix3d p_rr = cov.topLeftCorner<3, 3>();
  for (int j = 0; j < state.num_objects(); ++j) {
    ObjectPrediction& prediction = predictions[static_cast<size_t>(j)];
    const Eigen::Vector2d position = state.position(j);
    if ((position - sensor).norm() < kMinPredictedRange_m) continue;
    prediction.valid = true;
    prediction.range_bearing = PredictRangeBearing(robot, position, mount,
                                                   &prediction.jacobian_robot,
                                                   &prediction.jacobian_position);
    const int p = state.object(j).position_index;
    const auto& hr = prediction.jacobian_robot;
    const auto& hp = prediction.jacobian_position;
    const Eigen::Matrix2d cross = hr * cov.block<3, 2>(0, p) * hp.transpose();
    const Eigen::Matrix2d hph = hr * p_rr * hr.transpose() +
                                hp * cov.block<2, 2>(p, p) * hp.transpose() + cross +
                                cross.transpose();
    prediction.hph = 0.5 * (hph + hph.transpose());
  }
  return predictions;
}

double NormalizedInnovationSquared(const PointMeasurement& measurement,
                                   const ObjectPrediction& prediction, double gate_chi2) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!prediction.valid) return kInfinity;
  const double nu_r = measurement.range_bearing(0) - prediction.range_bearing(0);
  const double nu_b = WrapAngle(measurement.range_bearing(1) - prediction.range_bearing(1));
  const Eigen::Matrix2d s = prediction.hph + measurement.covariance;
  // Marginal lower bounds of the NIS (a 2-D Mahalanobis distance is at least each 1-D one).
  if (nu_b * nu_b >= gate_chi2 * s(1, 1) || nu_r * nu_r >= gate_chi2 * s(0, 0)) return kInfinity;
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  if (!(det > 0.0)) return kInfinity;
  return (s(1, 1) * nu_r * nu_r - (s(0, 1) + s(1, 0)) * nu_r * nu_b + s(0, 0) * nu_b * nu_b) /
         det;
}

std::vector<Candidate> GatePairs(const std::vector<PointMeasurement>& measurements,
                                 const std::vector<ObjectPrediction>& predictions,
                                 double gate_chi2) {
  std::vector<Candidate> pairs;
  for (size_t i = 0; i < measurements.size(); ++i) {
    for (size_t j = 0; j < predictions.size(); ++j) {
      const double nis = NormalizedInnovationSquared(measurements[i], predictions[j], gate_chi2);
      if (nis < gate_chi2) {
        pairs.push_back({static_cast<int>(i), static_cast<int>(j), nis});
      }
    }
  }
  return pairs;
}

CompatibilitySplit SplitCompatibility(const std::vector<Candidate>& pairs, int num_measurements,
                                      int num_objects) {
  std::vector<int> per_measurement(static_cast<size_t>(num_measurements), 0);
  std::vector<int> per_object(static_cast<size_t>(num_objects), 0);
  for (const Candidate& c : pairs) {
    ++per_measurement[static_cast<size_t>(c.measurement)];
    ++per_object[static_cast<size_t>(c.object)];
  }
  CompatibilitySplit split;
  for (const Candidate& c : pairs) {
    if (per_measurement[static_cast<size_t>(c.measurement)] == 1 &&
        per_object[static_cast<size_t>(c.object)] == 1) {
      split.unambiguous.push_back(c);
    } else {
      split.ambiguous.push_back(c);
    }
  }
  return split;
}

}  // namespace slammtt
