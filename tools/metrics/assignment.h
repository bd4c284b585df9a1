// Optimal assignment (Kuhn-Munkres / Hungarian method) for rectangular cost matrices, the
// building block of every matching-based metric here: OSPA and GOSPA (optimal sub-pattern
// assignment), CLEAR-MOT (Bernardin & Stiefelhagen 2008, section 2.1.1: "the Munkres algorithm"
// for the correspondences not carried over from the previous frame), the landmark-to-truth match
// of the map score and the per-scan match of the classification score.
//
// The solver is the shortest-augmenting-path form with row and column potentials (Kuhn 1955,
// Munkres 1957; the O(n^2 m) formulation used by Jonker & Volgenant 1987): one row is added at a
// time and the cheapest augmenting path in reduced costs is found Dijkstra-style.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace slammtt {

// Marks a pair that must not be assigned (for example a distance beyond the match threshold).
inline constexpr double kForbiddenCost = std::numeric_limits<double>::infinity();

struct Assignment {
  // For every row, the assigned column or -1.
  std::vector<int> row_to_col;
  // For every column, the assigned row or -1.
  std::vector<int> col_to_row;
  // Number of assigned pairs and the sum of their costs.
  int num_assigned = 0;
  double total_cost = 0.0;
};

// Solves min-cost assignment on a rows x cols matrix of non-negative costs, where an entry equal
// to kForbiddenCost (+infinity) forbids the pair. Among all assignments the solver first
// maximises the number of assigned (allowed) pairs and then minimises their total cost, which is
// what a thresholded match needs: never leave a pair within the threshold unmatched to save
// distance. Either dimension may be zero (nothing is assigned).
//
// Throws std::invalid_argument when an entry is negative or NaN: costs here are distances, so
// such a value is a bug in the caller, and the caller must reject non-finite inputs first.
Assignment SolveMinCostAssignment(const Eigen::MatrixXd& cost);

}  // namespace slammtt
