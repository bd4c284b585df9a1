// Individual compatibility of measurements with objects (paper Algorithm 2, lines 3-4, and
// eqs. 20-21): predicted observation h_i, innovation covariance S_i = H_i P H_i^T + R_i and the
// Mahalanobis distance (normalized innovation squared, NIS) of every measurement to every
// object; the compatibility matrix J marks the pairs inside a gate.
//
// Gates are thresholds on the NIS, which is chi-square with 2 degrees of freedom for a correct
// pair (e.g. 9.21 keeps 99 % of correct pairs). Cost: H P H^T is computed once per object
// (it does not depend on the measurement), then each pair costs a 2x2 solve; a pair whose
// range or bearing alone already exceeds the gate (nu_r^2 / S_rr >= gate or
// nu_b^2 / S_bb >= gate, both lower bounds of the NIS) is rejected without the solve.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "estimator/point_measurement.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// The predicted observation of one object at the current state.
struct ObjectPrediction {
  bool valid = false;  // false when the object sits at the sensor (bearing undefined)
  // Not judged in this scan although predicted (observation_predictions.h:
  // HoldBackUnsureReentries): valid is false, the rest of the prediction is kept so that a
  // measurement inside its gate starts no new object (scan_gating.h).
  bool held_back = false;
  Eigen::Vector2d range_bearing = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 2, 3> jacobian_robot = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix2d jacobian_position = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d hph = Eigen::Matrix2d::Zero();  // H P H^T (S without R)
};

// Predictions of every object of the state (index = object index).
std::vector<ObjectPrediction> PredictObservations(const SlamState& state,
                                                  const SensorMount& mount);

// A measurement-object pair with its NIS and, where a step chooses between competing pairs,
// its cost (PairCost below; 0 until a step computes it).
struct Candidate {
  int measurement = -1;
  int object = -1;
  double nis = 0.0;
  double cost = 0.0;
};

// What choosing a pair costs: its negative log-likelihood up to a constant, NIS + ln det S with
// S = H P H^T + R (the "generalized distance" of global-nearest-neighbour association, Blackman
// and Popoli 1999, section 6.3; the likelihood MLESAC scores with, Torr and Zisserman 2000).
// Choices between pairs that share a measurement use it rather than the NIS alone: the NIS of
// an object known to 2 m (a track coasting unseen, a one-scan-old object) is small for any
// measurement nearby, so by the NIS it would beat the landmark known to 2 cm that the
// measurement really belongs to. +infinity when S is not positive definite.
double PairCost(double nis, const Eigen::Matrix2d& innovation_covariance);
// The same with S = prediction.hph + measurement.covariance; +infinity for an invalid prediction.
double PairCost(const PointMeasurement& measurement, const ObjectPrediction& prediction,
                double nis);

// NIS of measurement z (with covariance R) against a prediction; +infinity when the prediction
// is invalid. `gate_chi2` only enables the cheap lower-bound rejection (returns +infinity for
// pairs proven to be >= gate_chi2); pass +infinity to always compute the exact value.
double NormalizedInnovationSquared(const PointMeasurement& measurement,
                                   const ObjectPrediction& prediction, double gate_chi2);

// Every pair (measurement i, object j) with NIS < gate_chi2, listed by measurement then object.
// Above kGatingBruteForcePairs pairs, objects are looked up by predicted bearing instead of
// trying every pair (a pair outside an object's bearing window cannot pass the gate; see the
// implementation); the result is the same list.
inline constexpr size_t kGatingBruteForcePairs = 1024;
inline constexpr double kMaxGatingWindow_rad = 0.5;
std::vector<Candidate> GatePairs(const std::vector<PointMeasurement>& measurements,
                                 const std::vector<ObjectPrediction>& predictions,
                                 double gate_chi2);

// The compatibility matrix J of Algorithm 2 (line 4), as the list of its non-zero pairs, split
// into the pairs that J settles (line 5: the only candidate of its measurement and of its
// object) and the ambiguous rest (measurements or objects with two or more candidates).
struct CompatibilitySplit {
  std::vector<Candidate> unambiguous;
  std::vector<Candidate> ambiguous;
};
CompatibilitySplit SplitCompatibility(const std::vector<Candidate>& pairs, int num_measurements,
                                      int num_objects);

}  // namespace slammtt
