// The estimator's models against numerical differentiation and against their own inverses.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "estimator/angle.h"
#include "estimator/constant_velocity_model.h"
#include "estimator/range_bearing_model.h"
#include "estimator/robot_motion_model.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

using testing::NumericalJacobian;

TEST(AngleTest, WrapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(WrapAngle(3.0 * M_PI + 0.1), -M_PI + 0.1, 1e-12);
  EXPECT_NEAR(WrapAngle(-0.5), -0.5, 1e-15);
  EXPECT_NEAR(WrapAngle(2.0 * M_PI), 0.0, 1e-15);
}

TEST(RobotMotionModelTest, FollowsEquationOne) {
  const Eigen::Vector3d pose(1.0, 2.0, 0.3);
  const Eigen::Vector3d next = PredictRobotPose(pose, {0.5, 0.2});
  EXPECT_NEAR(next(0), 1.0 + 0.5 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(next(1), 2.0 + 0.5 * std::sin(0.5), 1e-12);
  EXPECT_NEAR(next(2), 0.5, 1e-12);
}

TEST(RobotMotionModelTest, JacobiansMatchNumericalDerivatives) {
  const std::vector<Eigen::Vector3d> poses = {{0.0, 0.0, 0.0}, {1.0, -2.0, 3.1}, {-4.0, 2.5, -1.7}};
  const std::vector<OdometryIncrement> increments = {{0.3, 0.05}, {-0.2, 0.4}, {1.5, -0.3}};
  for (const Eigen::Vector3d& pose : poses) {
    for (const OdometryIncrement& u : increments) {
      Eigen::Matrix3d f;
      Eigen::Matrix<double, 3, 2> g;
      PredictRobotPose(pose, u, &f, &g);
      const Eigen::MatrixXd f_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return PredictRobotPose(x, u);
          },
          pose, {2});
      const Eigen::MatrixXd g_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return PredictRobotPose(pose, {x(0), x(1)});
          },
          Eigen::Vector2d(u.distance_m, u.rotation_rad), {2});
      EXPECT_LT((f - f_numerical).cwiseAbs().maxCoeff(), 1e-7);
      EXPECT_LT((g - g_numerical).cwiseAbs().maxCoeff(), 1e-7);
    }
  }
}

TEST(RobotMotionModelTest, HeadingDriftJacobiansMatchNumericalDerivatives) {
  const std::vector<Eigen::Vector4d> robots = {
      {0.0, 0.0, 0.0, 0.0}, {1.0, -2.0, 3.1, 0.009}, {-4.0, 2.5, -1.7, -0.015}};
  const std::vector<OdometryIncrement> increments = {{0.3, 0.05}, {-0.2, 0.4}, {1.5, -0.3}};
  for (const Eigen::Vector4d& robot : robots) {
    for (const OdometryIncrement& u : increments) {
      Eigen::Matrix4d f;
      Eigen::Matrix<double, 4, 2> g;
      PredictRobotPoseWithHeadingDrift(robot.head<3>(), robot(3), u, &f, &g);
      // The augmented transition: (pose, b) -> (eq. 1 with delta + b d, b).
      auto transition = [](const Eigen::Vector4d& x, const OdometryIncrement& v) {
        Eigen::VectorXd out(4);
        out.head<3>() = PredictRobotPoseWithHeadingDrift(x.head<3>(), x(3), v);
        out(3) = x(3);
        return out;
      };
      const Eigen::MatrixXd f_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return transition(Eigen::Vector4d(x), u);
          },
          robot, {2});
      const Eigen::MatrixXd g_numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            return transition(robot, {x(0), x(1)});
          },
          Eigen::Vector2d(u.distance_m, u.rotation_rad), {2});
      EXPECT_LT((f - f_numerical).cwiseAbs().maxCoeff(), 1e-7);
      EXPECT_LT((g - g_numerical).cwiseAbs().maxCoeff(), 1e-7);
      // The drift turns the robot by b d on top of the odometry (a wrapped difference).
      const Eigen::Vector3d plain = PredictRobotPose(robot.head<3>(), u);
      const Eigen::Vector3d drifted = PredictRobotPoseWithHeadingDrift(robot.head<3>(), robot(3), u);
      EXPECT_NEAR(WrapAngle(drifted(2) - plain(2)), robot(3) * u.distance_m, 1e-12);
    }
  }
}

TEST(RobotMotionModelTest, IncrementBetweenPosesInvertsEquationOne) {
  const Eigen::Vector3d from(0.5, -1.0, 3.0);
  for (const OdometryIncrement& u :
       {OdometryIncrement{0.4, 0.3}, OdometryIncrement{-0.25, -0.2}, OdometryIncrement{0.0, 1.0}}) {
    const Eigen::Vector3d to = PredictRobotPose(from, u);
    const OdometryIncrement back = IncrementBetweenOdometryPoses(from, to);
    EXPECT_NEAR(back.distance_m, u.distance_m, 1e-12);
    EXPECT_NEAR(back.rotation_rad, u.rotation_rad, 1e-12);
  }
}

TEST(RobotMotionModelTest, IncrementNoiseGrowsWithMotion) {
  OdometryNoiseOptions noise;
  const Eigen::Matrix2d still = OdometryIncrementCovariance({0.0, 0.0}, 0.1, noise);
  const Eigen::Matrix2d moving = OdometryIncrementCovariance({1.0, 0.5}, 0.1, noise);
  EXPECT_GT(still(0, 0), 0.0);
  EXPECT_GT(moving(0, 0), still(0, 0));
  EXPECT_GT(moving(1, 1), still(1, 1));
  EXPECT_DOUBLE_EQ(moving(0, 1), 0.0);
}

TEST(ConstantVelocityModelTest, TransitionAndNoiseFollowEquationsSevenAndEight) {
  const double dt = 0.125;
  const Eigen::Vector4d x(1.0, 2.0, 0.625, -0.75);
  Eigen::Matrix4d jacobian;
  const Eigen::Vector4d next = PredictConstantVelocity(x, dt, &jacobian);
  EXPECT_NEAR(next(0), 1.0 + 0.625 * dt, 1e-15);
  EXPECT_NEAR(next(1), 2.0 - 0.75 * dt, 1e-15);
  EXPECT_EQ(next.tail<2>(), x.tail<2>());
  const Eigen::MatrixXd numerical = NumericalJacobian(
      [&](const Eigen::VectorXd& s) -> Eigen::VectorXd { return PredictConstantVelocity(s, dt); },
      x);
  EXPECT_LT((jacobian - numerical).cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::Matrix4d q = ConstantVelocityProcessNoise(dt, 0.5);
  EXPECT_NEAR(q(0, 0), 0.25 * std::pow(dt, 4) / 4.0, 1e-15);
  EXPECT_NEAR(q(0, 2), 0.25 * std::pow(dt, 3) / 2.0, 1e-15);
  EXPECT_NEAR(q(2, 2), 0.25 * dt * dt, 1e-15);
  EXPECT_EQ(q(0, 1), 0.0);
  // Eq. 8 is G G^T sigma^2 with G = (dt^2/2, dt): rank 2, positive semi-definite.
  EXPECT_TRUE(q.isApprox(q.transpose()));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(q);
  EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-15);
}

TEST(ConstantVelocityModelTest, InPlaceOnAnObjectsSlotsIsTPTransposeT) {
  // A 9-state vector: robot (4), the object's position at 4-5, another state at 6, the object's
  // velocity at 7-8 (the slots need not be adjacent).
  const int p = 4;
  const int v = 7;
  const double dt = 0.3;
  Eigen::VectorXd x(9);
  x << 1.0, 2.0, 0.3, 0.001, 5.0, -2.0, 7.0, 0.8, -1.1;
  Eigen::MatrixXd a(9, 9);
  for (int r = 0; r < 9; ++r) {
    for (int c = 0; c < 9; ++c) a(r, c) = std::sin(1.0 + 3.0 * r + 7.0 * c);
  }
  const Eigen::MatrixXd cov = a * a.transpose() + Eigen::MatrixXd::Identity(9, 9);
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(9, 9);
  const Eigen::Matrix4d t_object = ConstantVelocityTransition(dt);
  const int slots[4] = {p, p + 1, v, v + 1};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) t(slots[r], slots[c]) = t_object(r, c);
  }
  Eigen::VectorXd mean = x;
  Eigen::MatrixXd in_place = cov;
  PredictConstantVelocityInPlace(dt, p, v, mean, in_place);
  EXPECT_LT((mean - t * x).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((in_place - t * cov * t.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  // The object's own 4-state prediction is the same model.
  const Eigen::Vector4d own(x(p), x(p + 1), x(v), x(v + 1));
  const Eigen::Vector4d next = PredictConstantVelocity(own, dt);
  EXPECT_EQ(next(0), mean(p));
  EXPECT_EQ(next(1), mean(p + 1));
  EXPECT_EQ(next(2), mean(v));
  EXPECT_EQ(next(3), mean(v + 1));
  // Only the object's position rows and columns change.
  for (int r = 0; r < 9; ++r) {
    for (int c = 0; c < 9; ++c) {
      if (r != p && r != p + 1 && c != p && c != p + 1) {
        EXPECT_EQ(in_place(r, c), cov(r, c));
      }
    }
  }
}

TEST(RangeBearingModelTest, PredictsEquationsTenAndEleven) {
  const SensorMount mount{0.2, 0.1};
  const Eigen::Vector3d robot(1.0, 1.0, M_PI / 2.0);
  // Sensor at (1 - 0.1, 1 + 0.2) = (0.9, 1.2); a point 3 m ahead of it along +y.
  const Eigen::Vector2d z = PredictRangeBearing(robot, Eigen::Vector2d(0.9, 4.2), mount);
  EXPECT_NEAR(z(0), 3.0, 1e-12);
  EXPECT_NEAR(z(1), 0.0, 1e-12);
  const Eigen::Vector2d left = PredictRangeBearing(robot, Eigen::Vector2d(-1.1, 1.2), mount);
  EXPECT_NEAR(left(0), 2.0, 1e-12);
  EXPECT_NEAR(left(1), M_PI / 2.0, 1e-12);
}

TEST(RangeBearingModelTest, JacobiansMatchNumericalDerivatives) {
  const std::vector<SensorMount> mounts = {{0.0, 0.0}, {0.15, -0.05}, {0.1, 0.05, 2.5}};
  const std::vector<Eigen::Vector3d> robots = {{0.0, 0.0, 0.0}, {2.0, -1.0, 2.9}, {-3.0, 4.0, -2.0}};
  const std::vector<Eigen::Vector2d> points = {{5.0, 0.5}, {-3.0, -0.2}, {1.0, 7.0}};
  for (const SensorMount& mount : mounts) {
    for (const Eigen::Vector3d& robot : robots) {
      for (const Eigen::Vector2d& point : points) {
        Eigen::Matrix<double, 2, 3> h_robot;
        Eigen::Matrix2d h_point;
        PredictRangeBearing(robot, point, mount, &h_robot, &h_point);
        const Eigen::MatrixXd h_robot_numerical = NumericalJacobian(
            [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
              return PredictRangeBearing(x, point, mount);
            },
            robot, {1});
        const Eigen::MatrixXd h_point_numerical = NumericalJacobian(
            [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
              return PredictRangeBearing(robot, x, mount);
            },
            point, {1});
        EXPECT_LT((h_robot - h_robot_numerical).cwiseAbs().maxCoeff(), 1e-7);
        EXPECT_LT((h_point - h_point_numerical).cwiseAbs().maxCoeff(), 1e-7);

        // The inverse model: its Jacobians, and that it inverts eq. 10.
        const Eigen::Vector2d z = PredictRangeBearing(robot, point, mount);
        Eigen::Matrix<double, 2, 3> g_robot;
        Eigen::Matrix2d g_z;
        const Eigen::Vector2d back = PointFromRangeBearing(robot, z, mount, &g_robot, &g_z);
        EXPECT_LT((back - point).norm(), 1e-12);
        const Eigen::MatrixXd g_robot_numerical = NumericalJacobian(
            [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
              return PointFromRangeBearing(x, z, mount);
            },
            robot);
        const Eigen::MatrixXd g_z_numerical = NumericalJacobian(
            [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
              return PointFromRangeBearing(robot, x, mount);
            },
            z);
        EXPECT_LT((g_robot - g_robot_numerical).cwiseAbs().maxCoeff(), 1e-7);
        EXPECT_LT((g_z - g_z_numerical).cwiseAbs().maxCoeff(), 1e-7);
      }
    }
  }
}

TEST(RangeBearingModelTest, ARotatedSensorMeasuresBearingsFromItsOwnHeading) {
  // Eq. 11 extended by the mount's yaw: the laser turned 90 degrees left of the robot sees a
  // point straight ahead of the robot at -90 degrees; the inverse places it back.
  const SensorMount rotated{0.2, 0.0, M_PI / 2};
  const Eigen::Vector3d robot(1.0, 2.0, 0.3);
  const Eigen::Vector2d ahead =
      robot.head<2>() + 3.2 * Eigen::Vector2d(std::cos(0.3), std::sin(0.3));
  const Eigen::Vector2d z = PredictRangeBearing(robot, ahead, rotated);
  EXPECT_NEAR(z(0), 3.0, 1e-12);
  EXPECT_NEAR(z(1), -M_PI / 2, 1e-12);
  const Eigen::Vector2d straight = PredictRangeBearing(robot, ahead, {0.2, 0.0, 0.0});
  EXPECT_NEAR(WrapAngle(straight(1) - z(1)), M_PI / 2, 1e-12);
  EXPECT_LT((PointFromRangeBearing(robot, z, rotated) - ahead).norm(), 1e-12);
}

TEST(RangeBearingModelTest, BearingDifferentiatesAcrossTheSeam) {
  // A point right behind the robot: bearing at +-pi, where a naive difference jumps by 2 pi.
  const Eigen::Vector3d robot(0.0, 0.0, 0.0);
  const Eigen::Vector2d point(-4.0, 1e-9);
  Eigen::Matrix2d h_point;
  PredictRangeBearing(robot, point, SensorMount{}, nullptr, &h_point);
  const Eigen::MatrixXd numerical = NumericalJacobian(
      [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
        return PredictRangeBearing(robot, x, SensorMount{});
      },
      point, {1});
  EXPECT_LT((h_point - numerical).cwiseAbs().maxCoeff(), 1e-7);
}

}  // namespace
}  // namespace slammtt
