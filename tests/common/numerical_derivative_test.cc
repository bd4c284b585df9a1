// The central-difference Jacobian of tests/support (what the model tests of every area check
// their analytic Jacobians against).
#include "tests/support/numerical_derivative.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slammtt::testing {
namespace {

TEST(NumericalJacobianTest, MatchesAKnownJacobian) {
  // f(x, y) = (x^2 y, sin(x) + 3 y): J = [2 x y, x^2; cos(x), 3].
  const auto f = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    return Eigen::Vector2d(v(0) * v(0) * v(1), std::sin(v(0)) + 3.0 * v(1));
  };
  const Eigen::Vector2d x(0.7, -1.3);
  Eigen::Matrix2d expected;
  expected << 2.0 * x(0) * x(1), x(0) * x(0), std::cos(x(0)), 3.0;
  const Eigen::MatrixXd numerical = NumericalJacobian(f, x);
  ASSERT_EQ(numerical.rows(), 2);
  ASSERT_EQ(numerical.cols(), 2);
  EXPECT_LT((numerical - expected).cwiseAbs().maxCoeff(), 1e-8);
  // A wrong analytic Jacobian is caught: the check has teeth.
  Eigen::Matrix2d wrong = expected;
  wrong(0, 1) += 1e-4;
  EXPECT_GT((numerical - wrong).cwiseAbs().maxCoeff(), 1e-5);
}

TEST(NumericalJacobianTest, AngleOutputsDifferentiateAcrossTheSeam) {
  // An angle output at pi: without wrapping, the difference across the seam is about 2 pi.
  const auto bearing = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    Eigen::VectorXd out(1);
    out(0) = std::atan2(v(1), v(0));
    return out;
  };
  const Eigen::Vector2d x(-2.0, 0.0);  // bearing pi, d/dy = 1 / x = -0.5
  EXPECT_NEAR(NumericalJacobian(bearing, x, {0})(0, 1), -0.5, 1e-8);
  EXPECT_GT(std::abs(NumericalJacobian(bearing, x)(0, 1)), 1e5);
}

}  // namespace
}  // namespace slammtt::testing
