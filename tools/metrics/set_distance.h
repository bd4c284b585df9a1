// Distances between a set of true object positions and a set of estimated positions, the
// per-scan multi-object tracking errors of the evaluation (docs/evaluation.md):
//
// - OSPA, optimal sub-pattern assignment (Schuhmacher, Vo & Vo, "A Consistent Metric for
//   Performance Evaluation of Multi-Object Filters", IEEE Trans. Signal Processing 56(8), 2008,
//   eq. 3): with m = min(|X|, |Y|), n = max(|X|, |Y|) and d_c(x, y) = min(c, |x - y|),
//     OSPA = ( (1/n) ( min over injections pi of sum_i d_c(x_i, y_pi(i))^p + c^p (n - m) ) )^(1/p)
//   It is normalised per object: a value in metres between 0 and c.
// - GOSPA, generalised OSPA (Rahmathullah, Garcia-Fernandez & Svensson, "Generalized optimal
//   sub-pattern assignment metric", FUSION 2017, eq. 1 and Proposition 1 for alpha = 2):
//     GOSPA = ( min over pi of sum_i d_c(x_i, y_pi(i))^p + (c^p / alpha) (n - m) )^(1/p)
//   Not normalised. With alpha = 2 it splits into localisation error of the assigned pairs
//   (distance < c), c^p/2 per missed true object and c^p/2 per false estimate.
//
// Both sets empty: distance 0 (both definitions leave this case open; 0 is the limit that makes
// a scan with nothing to see and nothing reported perfect). Positions must be finite: the caller
// rejects NaN/inf estimates before calling (std::invalid_argument otherwise).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace slammtt {

using PointSet = std::vector<Eigen::Vector2d>;

struct OspaResult {
  double distance_m = 0.0;      // OSPA distance
  double localisation_m = 0.0;  // ((1/n) sum of d_c^p over the optimal pairs)^(1/p)
  double cardinality_m = 0.0;   // ((1/n) c^p (n - m))^(1/p)
};

// OSPA between `truth` and `estimate` with cut-off `cutoff_m` > 0 and order `order` >= 1.
// std::invalid_argument for a parameter outside that range.
OspaResult Ospa(const PointSet& truth, const PointSet& estimate, double cutoff_m, double order);

struct GospaResult {
  double distance_m = 0.0;            // GOSPA distance
  // Decomposition (exact for alpha = 2; for other alpha only distance_m is meaningful):
  double localisation_pow = 0.0;      // sum of |x - y|^p over assigned pairs (distance < c)
  int num_assigned = 0;
  int num_missed = 0;                 // true objects without an estimate within c
  int num_false = 0;                  // estimates without a true object within c
};

// GOSPA with cut-off `cutoff_m` > 0, order `order` >= 1 and 0 < alpha <= 2.
GospaResult Gospa(const PointSet& truth, const PointSet& estimate, double cutoff_m, double order,
                  double alpha);

}  // namespace slammtt
