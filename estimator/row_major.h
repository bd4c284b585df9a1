// Square matrices as the messages carry them (every covariance of lcmtypes/*.lcm): row-major,
// kDim * kDim doubles. The one conversion the stages use (estimator_stage.cc,
// smoother_input_message.cc, smoother/smoother_stage.cc).
#pragma once

#include <Eigen/Core>

namespace slammtt {

// Writes m row by row into out[0 .. kDim * kDim).
template <int kDim>
void WriteRowMajor(const Eigen::Matrix<double, kDim, kDim>& m, double* out) {
  for (int r = 0; r < kDim; ++r) {
    for (int c = 0; c < kDim; ++c) out[kDim * r + c] = m(r, c);
  }
}

// The matrix written by WriteRowMajor.
template <int kDim>
Eigen::Matrix<double, kDim, kDim> ReadRowMajor(const double* in) {
  Eigen::Matrix<double, kDim, kDim> m;
  for (int r = 0; r < kDim; ++r) {
    for (int c = 0; c < kDim; ++c) m(r, c) = in[kDim * r + c];
  }
  return m;
}

}  // namespace slammtt
