#include "tools/metrics/assignment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slammtt {
namespace {

// Square-or-wide problem (rows <= cols), every entry finite. Returns row_to_col with every row
// assigned. Potentials: row_potential[i] + col_potential[j] <= cost(i, j) always holds, with
// equality on the assigned pairs; index 0 of the column arrays is a virtual column that holds
// the row being inserted.
std::vector<int> SolveWide(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> row_potential(rows + 1, 0.0);
  std::vector<double> col_potential(cols + 1, 0.0);
  std::vector<int> row_of_col(cols + 1, 0);   // 1-based row assigned to column j, 0 = free
  std::vector<int> previous_col(cols + 1, 0);  // augmenting-path tree

  for (int new_row = 1; new_row <= rows; ++new_row) {
    row_of_col[0] = new_row;
    int current_col = 0;
    std::vector<double> slack(cols + 1, inf);
    std::vector<bool> visited(cols + 1, false);
    do {
      visited[current_col] = true;
      const int row = row_of_col[current_col];
      double delta = inf;
      int next_col = -1;
      for (int j = 1; j <= cols; ++j) {
        if (visited[j]) continue;
        const double reduced = cost(row - 1, j - 1) - row_potential[row] - col_potential[j];
        if (reduced < slack[j]) {
          slack[j] = reduced;
          previous_col[j] = current_col;
        }
        if (slack[j] < delta) {
          delta = slack[j];
          next_col = j;
        }
      }
      // rows <= cols guarantees an unvisited column while the path is open.
      for (int j = 0; j <= cols; ++j) {
        if (visited[j]) {
          row_potential[row_of_col[j]] += delta;
          col_potential[j] -= delta;
        } else {
          slack[j] -= delta;
        }
      }
      current_col = next_col;
    } while (row_of_col[current_col] != 0);
    // Flip the augmenting path back to the virtual column.
    while (current_col != 0) {
      const int parent = previous_col[current_col];
      row_of_col[current_col] = row_of_col[parent];
      current_col = parent;
    }
  }
  std::vector<int> row_to_col(rows, -1);
  for (int j = 1; j <= cols; ++j) {
    if (row_of_col[j] != 0) row_to_col[row_of_col[j] - 1] = j - 1;
  }
  return row_to_col;
}

}  // namespace

Assignment SolveMinCostAssignment(const Eigen::MatrixXd& cost) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  Assignment result;
  result.row_to_col.assign(rows, -1);
  result.col_to_row.assign(cols, -1);
  if (rows == 0 || cols == 0) return result;

  double max_allowed = 0.0;
  bool any_allowed = false;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double c = cost(i, j);
      if (std::isnan(c) || c < 0.0) {
        throw std::invalid_argument("assignment cost (" + std::to_string(i) + ", " +
                                    std::to_string(j) + ") is negative or NaN");
      }
      if (c == kForbiddenCost) continue;
      any_allowed = true;
      max_allowed = std::max(max_allowed, c);
    }
  }
  if (!any_allowed) return result;

  // A forbidden pair costs more than every allowed pair of a full assignment together, so an
  // assignment with one forbidden pair fewer is always cheaper: the optimum has the largest
  // number of allowed pairs, and among those the least cost.
  const bool transpose = rows > cols;
  const int n = std::min(rows, cols);
  const double forbidden_substitute = (n + 1) * (max_allowed + 1.0);
  Eigen::MatrixXd finite = transpose ? Eigen::MatrixXd(cost.transpose()) : cost;
  for (Eigen::Index i = 0; i < finite.rows(); ++i) {
    for (Eigen::Index j = 0; j < finite.cols(); ++j) {
      if (finite(i, j) == kForbiddenCost) finite(i, j) = forbidden_substitute;
    }
  }
  const std::vector<int> wide = SolveWide(finite);
  for (int k = 0; k < static_cast<int>(wide.size()); ++k) {
    const int i = transpose ? wide[k] : k;
    const int j = transpose ? k : wide[k];
    if (cost(i, j) == kForbiddenCost) continue;
    result.row_to_col[i] = j;
    result.col_to_row[j] = i;
    ++result.num_assigned;
    result.total_cost += cost(i, j);
  }
  return result;
}

}  // namespace slammtt
