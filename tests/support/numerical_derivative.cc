#include "tests/support/numerical_derivative.h"

#include "common/angle.h"

namespace slammtt::testing {

Eigen::MatrixXd NumericalJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                  const Eigen::VectorXd& x, const std::vector<int>& angle_outputs,
                                  double step) {
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
