#include "estimator/gating.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "estimator/angle.h"

namespace slammtt {

std::vector<ObjectPrediction> PredictObservations(const SlamState& state,
                                                  const SensorMount& mount) {
  std::vector<ObjectPrediction> predictions(static_cast<size_t>(state.num_objects()));
  const Eigen::Vector3d robot = state.robot_pose();
  const Eigen::Vector2d sensor = SensorPosition(robot, mount);
  const auto cov = state.covariance();
  // The pose block only: the range-bearing Jacobian is zero on the heading drift state.
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

double PairCost(double nis, const Eigen::Matrix2d& innovation_covariance) {
  const Eigen::Matrix2d& s = innovation_covariance;
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  if (!(det > 0.0)) return std::numeric_limits<double>::infinity();
  return nis + std::log(det);
}

double PairCost(const PointMeasurement& measurement, const ObjectPrediction& prediction,
                double nis) {
  if (!prediction.valid) return std::numeric_limits<double>::infinity();
  return PairCost(nis, prediction.hph + measurement.covariance);
}

std::vector<Candidate> GatePairs(const std::vector<PointMeasurement>& measurements,
                                 const std::vector<ObjectPrediction>& predictions,
                                 double gate_chi2) {
  std::vector<Candidate> pairs;
  const size_t num_measurements = measurements.size();
  const size_t num_objects = predictions.size();
  auto try_pair = [&](size_t i, size_t j) {
    const double nis = NormalizedInnovationSquared(measurements[i], predictions[j], gate_chi2);
    if (nis < gate_chi2) pairs.push_back({static_cast<int>(i), static_cast<int>(j), nis});
  };
  if (num_measurements * num_objects <= kGatingBruteForcePairs || !std::isfinite(gate_chi2)) {
    for (size_t i = 0; i < num_measurements; ++i) {
      for (size_t j = 0; j < num_objects; ++j) try_pair(i, j);
    }
    return pairs;
  }
  // Bearing window: a pair passes only if nu_b^2 < gate * (H P H^T + R)_bb, so object j can
  // only pair with measurements within w_j = sqrt(gate * (hph_bb + max R_bb)) of its predicted
  // bearing. Objects with a window wider than kMaxGatingWindow_rad (close or very uncertain)
  // are tried against every measurement; the others are sorted by bearing and looked up with
  // the widest of their windows. The exact test below decides, so the result is the same as
  // trying every pair (and in the same order).
  double max_bearing_var = 0.0;
  for (const PointMeasurement& z : measurements) {
    max_bearing_var = std::max(max_bearing_var, z.covariance(1, 1));
  }
  std::vector<std::pair<double, int>> by_bearing;  // (predicted bearing, object)
  std::vector<int> everywhere;
  double window = 0.0;
  for (size_t j = 0; j < num_objects; ++j) {
    const ObjectPrediction& p = predictions[j];
    if (!p.valid) continue;
    // Slightly widened so that rounding in the exact test can never pass a pair outside it.
    const double w = std::sqrt(gate_chi2 * (p.hph(1, 1) + max_bearing_var)) * (1.0 + 1e-9) + 1e-12;
    const double bearing = p.range_bearing(1);
    if (w <= kMaxGatingWindow_rad && std::abs(bearing) <= M_PI) {
      by_bearing.emplace_back(bearing, static_cast<int>(j));
      window = std::max(window, w);
    } else {
      everywhere.push_back(static_cast<int>(j));
    }
  }
  std::sort(by_bearing.begin(), by_bearing.end());
  std::vector<int> candidates;
  auto add_range = [&](double from, double to) {
    auto it = std::lower_bound(by_bearing.begin(), by_bearing.end(),
                               std::make_pair(from, std::numeric_limits<int>::min()));
    for (; it != by_bearing.end() && it->first <= to; ++it) candidates.push_back(it->second);
  };
  for (size_t i = 0; i < num_measurements; ++i) {
    candidates.assign(everywhere.begin(), everywhere.end());
    const double b = WrapAngle(measurements[i].range_bearing(1));
    if (std::isfinite(b)) {
      // [b - window, b + window] on the circle; window < pi / 2, so the pieces never overlap.
      add_range(std::max(-M_PI, b - window), std::min(M_PI, b + window));
      if (b - window < -M_PI) add_range(b - window + 2.0 * M_PI, M_PI);
      if (b + window > M_PI) add_range(-M_PI, b + window - 2.0 * M_PI);
    }
    std::sort(candidates.begin(), candidates.end());
    for (int j : candidates) try_pair(i, static_cast<size_t>(j));
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
