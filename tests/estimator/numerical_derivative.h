// Central-difference Jacobians for checking the analytic ones (the GTSAM habit:
// gtsam/base/numericalDerivative.h). Angles in outputs are compared wrapped.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "estimator/angle.h"

namespace slammtt::testing {

// d f / d x at x, f: R^n -> R^m. Output components listed in `angle_outputs` are wrapped
// differences (so a bearing near +-pi differentiates correctly).
inline Eigen::MatrixXd NumericalJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    const std::vector<int>& angle_outputs = {}, double step = 1e-6) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd jacobian(f0.size(), x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    Eigen::VectorXd plus = x;
    Eigen::VectorXd minus = x;
    plus(k) += step;
    minus(k) -= step;
    Eigen::VectorXd difference = f(plus) - f(minus);
    for (int a : angle_outputs) difference(a) = WrapAngle(difference(a));
    jacobian.col(k) = difference / (2.0 * step);
  }
  return jacobian;
}

}  // namespace slammtt::testing
