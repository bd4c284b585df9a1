#include "smoother/sparse_cholesky.h"

#include <cholmod.h>

#include <algorithm>
#include <cstring>

namespace slammtt {

struct SparseCholesky::State {
  cholmod_common common;
  cholmod_sparse* matrix = nullptr;
  cholmod_factor* factor = nullptr;
  std::vector<double> to_root;  // ModifyWork's scratch, -1 everywhere between calls

  State() {
    cholmod_start(&common);
    common.print = 0;  // a pure library prints nothing
    common.error_handler = nullptr;
  }
  ~State() {
    Release();
    cholmod_finish(&common);
  }
  void Release() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    if (matrix != nullptr) cholmod_free_sparse(&matrix, &common);
  }
};

SparseCholesky::SparseCholesky() : state_(std::make_unique<State>()) {}
SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::Analyze(int n, const std::vector<int>& column_starts,
                             const std::vector<int>& rows, Form form, int trailing_natural,
                             const std::vector<char>* ordered_last) {
  State& s = *state_;
  s.Release();
  factorized_ = false;
  n_ = n;
  const size_t nonzeros = rows.size();
  s.matrix = cholmod_allocate_sparse(n, n, nonzeros, /*sorted=*/1, /*packed=*/1, /*stype=*/1,
                                     CHOLMOD_REAL, &s.common);
  if (s.matrix == nullptr) return false;
  std::memcpy(s.matrix->p, column_starts.data(), sizeof(int) * (n + 1));
  std::memcpy(s.matrix->i, rows.data(), sizeof(int) * nonzeros);
  std::fill_n(static_cast<double*>(s.matrix->x), nonzeros, 0.0);

  s.common.supernodal = form == Form::kSupernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  s.common.final_ll = form == Form::kSupernodal ? 1 : 0;
  s.common.nmethods = 0;  // CHOLMOD's choice: AMD, METIS if AMD fills badly
  s.common.postorder = 1;
  if (ordered_last != nullptr &&
      ordered_last->size() != static_cast<size_t>(n - trailing_natural)) {
    return false;  // one flag per leading index
  }
  if (trailing_natural == 0 && ordered_last == nullptr) {
    s.factor = cholmod_analyze(s.matrix, &s.common);
  } else {
    // Order the leading part as CHOLMOD chooses (or by CAMD, the flagged indices after the
    // others), then keep the trailing indices last: they are isolated diagonal entries now, so
    // where they go changes no fill of the rest.
    const int leading = n - trailing_natural;
    std::vector<int> chosen(n);
    if (ordered_last != nullptr) {
      std::vector<int> constraint(n, 2);
      for (int k = 0; k < leading; ++k) constraint[k] = (*ordered_last)[k] ? 1 : 0;
      if (!cholmod_camd(s.matrix, nullptr, 0, constraint.data(), chosen.data(), &s.common)) {
        return false;
      }
    } else {
      cholmod_factor* first = cholmod_analyze(s.matrix, &s.common);
      if (first == nullptr) return false;
      std::memcpy(chosen.data(), first->Perm, sizeof(int) * n);
      cholmod_free_factor(&first, &s.common);
    }
    std::vector<int> permutation;
    permutation.reserve(n);
    for (int k = 0; k < n; ++k) {
      if (chosen[k] < leading) permutation.push_back(chosen[k]);
    }
    for (int k = leading; k < n; ++k) permutation.push_back(k);
    s.common.nmethods = 1;
    s.common.method[0].ordering = CHOLMOD_GIVEN;
    s.common.postorder = 0;  // a postorder could move the trailing slots forward
    s.factor = cholmod_analyze_p(s.matrix, permutation.data(), nullptr, 0, &s.common);
    s.common.nmethods = 0;
    s.common.postorder = 1;
  }
  if (s.factor == nullptr) return false;
  position_.assign(n, 0);
  const int* perm = static_cast<const int*>(s.factor->Perm);
  for (int k = 0; k < n; ++k) position_[perm[k]] = k;
  return true;
}

bool SparseCholesky::Factorize(const std::vector<double>& values) {
  State& s = *state_;
  factorized_ = false;
  if (s.matrix == nullptr || s.factor == nullptr) return false;
  std::memcpy(s.matrix->x, values.data(), sizeof(double) * values.size());
  s.common.quick_return_if_not_posdef = 1;
  if (!cholmod_factorize(s.matrix, s.factor, &s.common)) return false;
  if (s.common.status != CHOLMOD_OK) return false;  // CHOLMOD_NOT_POSDEF among others
  factorized_ = true;
  return true;
}

bool SparseCholesky::Modify(bool update, const std::vector<SparseColumn>& columns) {
  State& s = *state_;
  if (!factorized_ || columns.empty()) return factorized_;
  size_t nonzeros = 0;
  for (const SparseColumn& column : columns) nonzeros += column.rows.size();
  cholmod_sparse* c = cholmod_allocate_sparse(n_, columns.size(), nonzeros, /*sorted=*/1,
                                              /*packed=*/1, /*stype=*/0, CHOLMOD_REAL,
                                              &s.common);
  if (c == nullptr) {
    factorized_ = false;
    return false;
  }
  int* p = static_cast<int*>(c->p);
  int* i = static_cast<int*>(c->i);
  double* x = static_cast<double*>(c->x);
  // cholmod_updown takes C in the factor's ordering, rows sorted within each column.
  std::vector<std::vector<std::pair<int, double>>> permuted(columns.size());
  for (size_t k = 0; k < columns.size(); ++k) {
    for (size_t e = 0; e < columns[k].rows.size(); ++e) {
      permuted[k].emplace_back(position_[columns[k].rows[e]], columns[k].values[e]);
    }
    std::sort(permuted[k].begin(), permuted[k].end());
  }
  // It runs the columns in groups of up to 8, each group along the union of its columns' paths
  // in the elimination tree (from a column's first row to the root): columns sorted by their
  // first row share most of their paths.
  std::vector<std::pair<int, size_t>> order;
  order.reserve(columns.size());
  for (size_t k = 0; k < columns.size(); ++k) {
    order.emplace_back(permuted[k].empty() ? n_ : permuted[k].front().first, k);
  }
  std::sort(order.begin(), order.end());
  size_t at = 0;
  for (size_t slot = 0; slot < order.size(); ++slot) {
    p[slot] = static_cast<int>(at);
    for (const auto& [row, value] : permuted[order[slot].second]) {
      i[at] = row;
      x[at] = value;
      ++at;
    }
  }
  p[columns.size()] = static_cast<int>(at);
  const bool ok = cholmod_updown(update ? 1 : 0, c, s.factor, &s.common) &&
                  s.common.status == CHOLMOD_OK;
  cholmod_free_sparse(&c, &s.common);
  if (!ok) factorized_ = false;
  return ok;
}

double SparseCholesky::ModifyWork(const std::vector<SparseColumn>& columns) const {
  if (!factorized_ || state_->factor == nullptr || state_->factor->is_super) return 0.0;
  const cholmod_factor* l = state_->factor;
  const int* starts = static_cast<const int*>(l->p);
  const int* rows = static_cast<const int*>(l->i);
  const int* counts = static_cast<const int*>(l->nz);
  // The parent of column j in the elimination tree: its first row below the diagonal (the
  // diagonal comes first in a simplicial column; n_ for a root).
  const auto parent = [&](int j) {
    int first = n_;
    for (int e = starts[j] + 1; e < starts[j] + counts[j]; ++e) first = std::min(first, rows[e]);
    return first;
  };
  // Entries from each column up to the root, filled in along the walks (paths share their top);
  // the scratch is reset where it was written, so a call costs its paths, not n.
  std::vector<double>& to_root = state_->to_root;
  to_root.resize(n_, -1.0);
  std::vector<int> walk;
  std::vector<int> written;
  double work = 0.0;
  for (const SparseColumn& column : columns) {
    if (column.rows.empty()) continue;
    int first = n_;
    for (int row : column.rows) first = std::min(first, position_[row]);
    int j = first;
    while (j < n_ && to_root[j] < 0.0) {
      walk.push_back(j);
      j = parent(j);
    }
    double above = j < n_ ? to_root[j] : 0.0;
    for (; !walk.empty(); walk.pop_back()) {
      above += counts[walk.back()];
      to_root[walk.back()] = above;
      written.push_back(walk.back());
    }
    work += to_root[first];
  }
  for (int j : written) to_root[j] = -1.0;
  return work;
}

double SparseCholesky::FactorizationWork() const {
  if (!factorized_ || state_->factor == nullptr || state_->factor->is_super) return 0.0;
  const cholmod_factor* l = state_->factor;
  const int* counts = static_cast<const int*>(l->nz);
  double work = 0.0;
  for (size_t k = 0; k < l->n; ++k) work += static_cast<double>(counts[k]) * counts[k];
  return work;
}

Eigen::MatrixXd SparseCholesky::SolveColumns(const Eigen::MatrixXd& b) const {
  State& s = *state_;
  if (!factorized_ || b.rows() != n_) return Eigen::MatrixXd();
  cholmod_dense* rhs = cholmod_allocate_dense(n_, b.cols(), n_, CHOLMOD_REAL, &s.common);
  if (rhs == nullptr) return Eigen::MatrixXd();
  std::memcpy(rhs->x, b.data(), sizeof(double) * b.size());
  cholmod_dense* solution = cholmod_solve(CHOLMOD_A, s.factor, rhs, &s.common);
  cholmod_free_dense(&rhs, &s.common);
  if (solution == nullptr) return Eigen::MatrixXd();
  Eigen::MatrixXd x =
      Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(solution->x), n_, b.cols());
  cholmod_free_dense(&solution, &s.common);
  return x;
}

Eigen::VectorXd SparseCholesky::Solve(const Eigen::VectorXd& b) const {
  const Eigen::MatrixXd x = SolveColumns(b);
  if (x.size() == 0) return Eigen::VectorXd();
  return x.col(0);
}

double SparseCholesky::factor_nonzeros() const {
  if (!factorized_ || state_->factor == nullptr) return 0.0;
  const cholmod_factor* l = state_->factor;
  if (l->is_super) return static_cast<double>(l->xsize);
  const int* counts = static_cast<const int*>(l->nz);
  double total = 0.0;
  for (size_t k = 0; k < l->n; ++k) total += counts[k];
  return total;
}

}  // namespace slammtt
