#include "tools/metrics/set_distance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/metrics/assignment.h"

namespace slammtt {
namespace {

void CheckParameters(double cutoff_m, double order) {
  if (!(cutoff_m > 0.0) || !std::isfinite(cutoff_m)) {
    throw std::invalid_argument("set distance: cut-off must be a positive number");
  }
  if (!(order >= 1.0) || !std::isfinite(order)) {
    throw std::invalid_argument("set distance: order must be >= 1");
  }
}

void CheckFinite(const PointSet& points) {
  for (const Eigen::Vector2d& p : points) {
    if (!p.allFinite()) throw std::invalid_argument("set distance: non-finite position");
  }
}

// Pairwise cut-off distances raised to the power p, rows = truth, columns = estimate.
Eigen::MatrixXd CutoffCostMatrix(const PointSet& truth, const PointSet& estimate,
                                 double cutoff_m, double order) {
  Eigen::MatrixXd cost(truth.size(), estimate.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    for (size_t j = 0; j < estimate.size(); ++j) {
      const double d = std::min(cutoff_m, (truth[i] - estimate[j]).norm());
      cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = std::pow(d, order);
    }
  }
  return cost;
}

}  // namespace

OspaResult Ospa(const PointSet& truth, const PointSet& estimate, double cutoff_m, double order) {
  CheckParameters(cutoff_m, order);
  CheckFinite(truth);
  CheckFinite(estimate);
  OspaResult result;
  const size_t n = std::max(truth.size(), estimate.size());
  const size_t m = std::min(truth.size(), estimate.size());
  if (n == 0) return result;
  const Assignment assignment =
      SolveMinCostAssignment(CutoffCostMatrix(truth, estimate, cutoff_m, order));
  const double localisation_pow = assignment.total_cost;
  const double cardinality_pow = std::pow(cutoff_m, order) * static_cast<double>(n - m);
  const double inv_n = 1.0 / static_cast<double>(n);
  result.distance_m = std::pow(inv_n * (localisation_pow + cardinality_pow), 1.0 / order);
  result.localisation_m = std::pow(inv_n * localisation_pow, 1.0 / order);
  result.cardinality_m = std::pow(inv_n * cardinality_pow, 1.0 / order);
  return result;
}

GospaResult Gospa(const PointSet& truth, const PointSet& estimate, double cutoff_m, double order,
                  double alpha) {
  CheckParameters(cutoff_m, order);
  if (!(alpha > 0.0 && alpha <= 2.0)) {
    throw std::invalid_argument("GOSPA: alpha must be in (0, 2]");
  }
  CheckFinite(truth);
  CheckFinite(estimate);
  GospaResult result;
  const size_t n = std::max(truth.size(), estimate.size());
  const size_t m = std::min(truth.size(), estimate.size());
  if (n == 0) return result;
  const Assignment assignment =
      SolveMinCostAssignment(CutoffCostMatrix(truth, estimate, cutoff_m, order));
  const double c_pow = std::pow(cutoff_m, order);
  const double total_pow =
      assignment.total_cost + c_pow / alpha * static_cast<double>(n - m);
  result.distance_m = std::pow(total_pow, 1.0 / order);
  // A pair at the cut-off or beyond costs c^p = c^p/2 + c^p/2: one miss plus one false estimate.
  for (size_t i = 0; i < truth.size(); ++i) {
    const int j = assignment.row_to_col[i];
    if (j < 0) continue;
    const double d = (truth[i] - estimate[static_cast<size_t>(j)]).norm();
    if (d < cutoff_m) {
      ++result.num_assigned;
      result.localisation_pow += std::pow(d, order);
    }
  }
  result.num_missed = static_cast<int>(truth.size()) - result.num_assigned;
  result.num_false = static_cast<int>(estimate.size()) - result.num_assigned;
  return result;
}

}  // namespace slammtt
