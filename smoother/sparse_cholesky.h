// A symmetric positive definite sparse matrix factorised by CHOLMOD (SuiteSparse), the one
// place the project calls CHOLMOD. The matrix is given by the pattern of its upper triangle
// (compressed columns, rows sorted within each column) and its values; the caller keeps the
// pattern and rewrites the values.
//
// Two uses:
// - batch: Analyze once per pattern (CHOLMOD picks the fill-reducing ordering: AMD, and METIS
//   when AMD's fill is high, Common->nmethods = 0), then Factorize (supernodal LL^T, the
//   symbolic analysis reused) and Solve as often as the values change;
// - incremental: Analyze with `trailing_natural` indices kept last, in their natural order (the
//   slots new variables will take, so that adding them touches only the end of the factor),
//   Factorize once (simplicial LDL^T), then Modify by rank-k updates and downdates
//   (cholmod_updown: LDL^T +- C C^T) as factors arrive or are relinearised, and Solve.
// Marginal covariance blocks come from Solve on unit vectors (SolveColumns): CHOLMOD has no
// sparse-inverse routine, and the smoother asks for a few small blocks (a pose, the
// landmarks), each costing one forward and one back substitution per column.
//
// Failure (not positive definite, CHOLMOD out of memory) is a return value, never a crash.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace slammtt {

class SparseCholesky {
 public:
  enum class Form { kSupernodal, kSimplicial };

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis of the n x n pattern (upper triangle, column starts of size n + 1, row
  // indices sorted per column, diagonal present in every column). Indices >= n -
  // trailing_natural are ordered last, in natural order. With `ordered_last` (one flag per
  // leading index), the flagged indices are ordered after the others (constrained minimum
  // degree, CHOLMOD's CAMD), as ISAM2 orders the variables of the newest factors last: later
  // rank updates on them then run along short paths of the elimination tree. False if CHOLMOD
  // fails or `ordered_last` does not have n - trailing_natural flags.
  bool Analyze(int n, const std::vector<int>& column_starts, const std::vector<int>& rows,
               Form form, int trailing_natural = 0,
               const std::vector<char>* ordered_last = nullptr);

  // Numeric factorisation of the analysed pattern with these values (one per row index). False
  // if the matrix is not positive definite.
  bool Factorize(const std::vector<double>& values);

  // LDL^T += C C^T (update) or -= C C^T (downdate). C is n x k, given column by column as
  // (original row index, value) lists. False if the result is not positive definite or
  // CHOLMOD fails; the factor is then to be rebuilt.
  struct SparseColumn {
    std::vector<int> rows;
    std::vector<double> values;
  };
  bool Modify(bool update, const std::vector<SparseColumn>& columns);

  // The work Modify(columns) would do, counted without doing it: for each column, the factor's
  // entries along its path in the elimination tree, from the column's first row (in the
  // factor's ordering) to the root, summed over the columns. cholmod_updown runs every column
  // along that path (in groups of up to 8 sharing it), so a column on a variable eliminated
  // early, far from the root, costs the factor's whole height. 0 before a factorisation.
  double ModifyWork(const std::vector<SparseColumn>& columns) const;
  // The work of a simplicial factorisation with the factor's present fill, in the same unit:
  // the sum over its columns of the squared entry counts.
  double FactorizationWork() const;

  // x with A x = b (A the factorised matrix). Empty on failure.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;
  // A^-1 B for the columns of B.
  Eigen::MatrixXd SolveColumns(const Eigen::MatrixXd& b) const;

  bool factorized() const { return factorized_; }
  int dimension() const { return n_; }
  // Nonzeros of the factor (a fill measure), 0 before a factorisation.
  double factor_nonzeros() const;
  // Position of original index i in the factor's ordering.
  int PositionOf(int i) const { return position_[i]; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  int n_ = 0;
  bool factorized_ = false;
  std::vector<int> position_;
};

}  // namespace slammtt
