// The line observation model (estimator/line_model.h): values on hand-made cases, and every
// Jacobian against central differences of the very function the filter calls.
#include "estimator/line_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/angle.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

using testing::NumericalJacobian;

TEST(LineModelTest, WallAheadOfARobotAtTheOrigin) {
  // The wall x = 3 seen from the origin facing +x: 3 m ahead, normal along the heading.
  const Eigen::Vector2d z = PredictLineObservation(Eigen::Vector3d::Zero(), {3.0, 0.0}, {});
  EXPECT_NEAR(z(0), 3.0, 1e-15);
  EXPECT_NEAR(z(1), 0.0, 1e-15);
  // Facing +y with the laser 0.5 m ahead: the wall is to the right, 3 m away.
  const Eigen::Vector2d turned =
      PredictLineObservation({0.0, 0.0, M_PI / 2}, {3.0, 0.0}, {0.5, 0.0});
  EXPECT_NEAR(turned(0), 3.0, 1e-12);
  EXPECT_NEAR(turned(1), -M_PI / 2, 1e-12);
}

TEST(LineModelTest, LineBehindTheMapOriginIsSeenWithPositiveRho) {
  // x = 3 written as rho = -3, alpha = pi. From (5, 0) facing +x it is a wall 2 m behind, its
  // normal from the sensor pointing back along -x.
  bool flipped = false;
  const Eigen::Vector2d z =
      PredictLineObservation({5.0, 0.0, 0.0}, {-3.0, M_PI}, {}, nullptr, nullptr, &flipped);
  EXPECT_FALSE(flipped);  // rho_s = -3 - (5 * -1) = 2
  EXPECT_NEAR(z(0), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(z(1)), M_PI, 1e-12);
  // The same line from the origin: rho_s = -3 < 0 flips to 3 along alpha 0.
  const Eigen::Vector2d from_origin =
      PredictLineObservation(Eigen::Vector3d::Zero(), {-3.0, M_PI}, {}, nullptr, nullptr,
                             &flipped);
  EXPECT_TRUE(flipped);
  EXPECT_NEAR(from_origin(0), 3.0, 1e-12);
  EXPECT_NEAR(from_origin(1), 0.0, 1e-12);
}

TEST(LineModelTest, InverseGivesTheLineBack) {
  const SensorMount mount{0.2, -0.1};
  const std::vector<Eigen::Vector3d> robots = {
      {0.0, 0.0, 0.0}, {1.5, -2.0, 0.7}, {-3.0, 4.0, -2.9}, {10.0, 0.5, M_PI}};
  const std::vector<Eigen::Vector2d> lines = {
      {4.0, 0.3}, {-2.0, 1.2}, {0.5, -2.5}, {7.0, M_PI}};
  for (const Eigen::Vector3d& robot : robots) {
    for (const Eigen::Vector2d& line : lines) {
      const Eigen::Vector2d z = PredictLineObservation(robot, line, mount);
      ASSERT_GE(z(0), 0.0);
      const Eigen::Vector2d back = LineFromObservation(robot, z, mount);
      // The same line: every point of the original lies on it.
      const Eigen::Vector2d n(std::cos(back(1)), std::sin(back(1)));
      for (double t : {-4.0, 0.0, 3.0}) {
        EXPECT_NEAR(PointOnLine(line, t).dot(n), back(0), 1e-9);
      }
    }
  }
}

TEST(LineModelTest, ARotatedSensorSeesTheLineTurnedByItsYaw) {
  // The wall x = 3 from the origin, the laser turned 30 degrees left: the wall's normal lies 30
  // degrees to the laser's right; the inverse gives the wall back.
  const SensorMount rotated{0.0, 0.0, M_PI / 6};
  const Eigen::Vector2d z = PredictLineObservation(Eigen::Vector3d::Zero(), {3.0, 0.0}, rotated);
  EXPECT_NEAR(z(0), 3.0, 1e-12);
  EXPECT_NEAR(z(1), -M_PI / 6, 1e-12);
  const Eigen::Vector2d back = LineFromObservation(Eigen::Vector3d::Zero(), z, rotated);
  EXPECT_NEAR(back(0), 3.0, 1e-12);
  EXPECT_NEAR(back(1), 0.0, 1e-12);
  // A point 1 m along the laser's x axis.
  const Eigen::Vector2d p = SensorPointToMap(Eigen::Vector3d::Zero(), rotated, {1.0, 0.0});
  EXPECT_NEAR(p(0), std::cos(M_PI / 6), 1e-12);
  EXPECT_NEAR(p(1), std::sin(M_PI / 6), 1e-12);
}

TEST(LineModelTest, JacobiansMatchNumericalDerivatives) {
  for (const SensorMount& mount : {SensorMount{0.3, 0.1, 0.0}, SensorMount{-0.1, 0.2, -2.0}}) {
  const std::vector<Eigen::Vector3d> robots = {
      {0.0, 0.0, 0.0}, {1.5, -2.0, 0.7}, {-3.0, 4.0, -2.9}, {2.0, 1.0, 3.1}};
  // Lines seen from both sides (flipped and not), normals near +-pi.
  const std::vector<Eigen::Vector2d> lines = {
      {4.0, 0.3}, {-2.0, 1.2}, {0.5, -2.5}, {7.0, M_PI}, {-6.0, -3.1}};
  int flipped_cases = 0;
  for (const Eigen::Vector3d& robot : robots) {
    for (const Eigen::Vector2d& line : lines) {
      Eigen::Matrix<double, 2, 3> h_robot;
      Eigen::Matrix2d h_line;
      bool flipped = false;
      const Eigen::Vector2d z =
          PredictLineObservation(robot, line, mount, &h_robot, &h_line, &flipped);
      ASSERT_GT(z(0), 0.1);  // away from the flip
      flipped_cases += flipped ? 1 : 0;
      const Eigen::MatrixXd h_robot_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return PredictLineObservation(x, line, mount);
          },
          robot, {1});
      const Eigen::MatrixXd h_line_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return PredictLineObservation(robot, x, mount);
          },
          line, {1});
      EXPECT_LT((h_robot - h_robot_numerical).cwiseAbs().maxCoeff(), 1e-7);
      EXPECT_LT((h_line - h_line_numerical).cwiseAbs().maxCoeff(), 1e-7);

      Eigen::Matrix<double, 2, 3> g_robot;
      Eigen::Matrix2d g_observation;
      LineFromObservation(robot, z, mount, &g_robot, &g_observation);
      const Eigen::MatrixXd g_robot_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return LineFromObservation(x, z, mount);
          },
          robot, {1});
      const Eigen::MatrixXd g_observation_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return LineFromObservation(robot, x, mount);
          },
          z, {1});
      EXPECT_LT((g_robot - g_robot_numerical).cwiseAbs().maxCoeff(), 1e-7);
      EXPECT_LT((g_observation - g_observation_numerical).cwiseAbs().maxCoeff(), 1e-7);
    }
  }
  EXPECT_GT(flipped_cases, 0);  // both branches of the sign were differentiated
  EXPECT_LT(flipped_cases, static_cast<int>(robots.size() * lines.size()));
  }
}

TEST(LineModelTest, ExtentCoordinatesRoundTrip) {
  const Eigen::Vector2d line(2.0, 0.4);
  for (double t : {-3.0, 0.0, 1.25}) {
    const Eigen::Vector2d p = PointOnLine(line, t);
    EXPECT_NEAR(p.dot(Eigen::Vector2d(std::cos(0.4), std::sin(0.4))), 2.0, 1e-12);
    EXPECT_NEAR(PositionAlongLine(line, p), t, 1e-12);
  }
  // A sensor point 1 m ahead of a laser mounted 0.5 m ahead of a robot at (1, 1) facing +y.
  const Eigen::Vector2d q = SensorPointToMap({1.0, 1.0, M_PI / 2}, {0.5, 0.0}, {1.0, 0.0});
  EXPECT_NEAR(q(0), 1.0, 1e-12);
  EXPECT_NEAR(q(1), 2.5, 1e-12);
}

}  // namespace
}  // namespace slammtt
