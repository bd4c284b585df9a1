// Central-difference Jacobians for checking analytic ones (the GTSAM habit:
// gtsam/base/numericalDerivative.h): every model whose Jacobian the code computes by hand is
// tested against these. Library slammtt_test_numerical; include as
// "tests/support/numerical_derivative.h" (namespace slammtt::testing).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace slammtt::testing {

// d f / d x at x for f: R^n -> R^m, by central differences with `step` on each input.
// Output components listed in `angle_outputs` are differenced wrapped to (-pi, pi] (so a bearing
// near +-pi differentiates correctly).
Eigen::MatrixXd NumericalJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                  const Eigen::VectorXd& x,
                                  const std::vector<int>& angle_outputs = {}, double step = 1e-6);

}  // namespace slammtt::testing
