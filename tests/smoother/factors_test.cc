// Every analytic Jacobian of the smoother's models against central differences
// (tests/support/numerical_derivative.h), at random poses and points, with a laser mount
// offset for the range-bearing model.
#include <gtest/gtest.h>

#include <random>

#include "smoother/factors.h"
#include "geometry/pose2.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

using testing::NumericalJacobian;

class FactorJacobianTest : public ::testing::Test {
 protected:
  Eigen::Vector3d RandomPose() {
    std::uniform_real_distribution<double> position(-20.0, 20.0);
    std::uniform_real_distribution<double> angle(-3.1, 3.1);
    return Eigen::Vector3d(position(rng_), position(rng_), angle(rng_));
  }
  Eigen::Vector2d RandomPoint() {
    std::uniform_real_distribution<double> position(-20.0, 20.0);
    return Eigen::Vector2d(position(rng_), position(rng_));
  }
  std::mt19937_64 rng_{20261201};
};

constexpr int kTrials = 200;
constexpr double kTolerance = 1e-6;

TEST_F(FactorJacobianTest, PoseLogarithmMatchesNumerical) {
  for (int trial = 0; trial < kTrials; ++trial) {
    Eigen::Vector3d motion = RandomPose() * 0.1;
    if (trial % 4 == 0) motion(2) *= 1e-4;  // the series branch near theta = 0
    Eigen::Matrix3d analytic;
    PoseLogarithm(motion, &analytic);
    const auto f = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return PoseLogarithm(Eigen::Vector3d(x));
    };
    EXPECT_LT((analytic - NumericalJacobian(f, motion, {2})).cwiseAbs().maxCoeff(), kTolerance)
        << motion.transpose();
  }
}

TEST_F(FactorJacobianTest, PoseLogarithmInvertsComposition) {
  // Log of a pure rotation is (0, 0, theta); of a pure translation the translation itself.
  EXPECT_LT((PoseLogarithm(Eigen::Vector3d(0, 0, 0.7)) - Eigen::Vector3d(0, 0, 0.7)).norm(),
            1e-15);
  EXPECT_LT((PoseLogarithm(Eigen::Vector3d(2, -1, 0)) - Eigen::Vector3d(2, -1, 0)).norm(),
            1e-15);
  // A quarter turn along an arc of radius 1: the twist is (pi/2, 0, pi/2).
  const Eigen::Vector3d arc(1.0, 1.0, M_PI / 2);
  EXPECT_LT((PoseLogarithm(arc) - Eigen::Vector3d(M_PI / 2, 0, M_PI / 2)).norm(), 1e-12);
}

TEST_F(FactorJacobianTest, PoseExponentialInvertsTheLogarithm) {
  for (int trial = 0; trial < kTrials; ++trial) {
    Eigen::Vector3d twist = RandomPose() * 0.1;
    if (trial % 4 == 0) twist(2) *= 1e-4;  // the series branch near omega = 0
    EXPECT_LT((PoseLogarithm(PoseExponential(twist)) - twist).cwiseAbs().maxCoeff(), 1e-12)
        << twist.transpose();
  }
  // GTSAM 4.3.0 (PyPI): Pose2(1, 2, 0.5).retract((0.1, 0.2, 0.3)) = (0.958726, 2.21891, 0.8).
  const Eigen::Vector3d moved =
      RetractPoseExponential(Eigen::Vector3d(1, 2, 0.5), Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_LT((moved - Eigen::Vector3d(0.958726, 2.21891, 0.8)).cwiseAbs().maxCoeff(), 1e-5);
}

TEST_F(FactorJacobianTest, RetractionJacobianAtZeroMatchesNumerical) {
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d pose = RandomPose();
    const auto f = [&](const Eigen::VectorXd& delta) -> Eigen::VectorXd {
      return RetractPoseExponential(pose, Eigen::Vector3d(delta));
    };
    EXPECT_LT((RetractionJacobianAtZero(pose(2)) -
               NumericalJacobian(f, Eigen::Vector3d::Zero(), {2}))
                  .cwiseAbs()
                  .maxCoeff(),
              kTolerance)
        << pose.transpose();
  }
}

TEST_F(FactorJacobianTest, OdometryMatchesNumerical) {
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d xi = RandomPose();
    const Eigen::Vector3d xj = ComposePoses(xi, RandomPose() * 0.05);
    const Eigen::Vector3d measured = RandomPose() * 0.05;
    Eigen::Matrix3d ji;
    Eigen::Matrix3d jj;
    OdometryResidual(xi, xj, measured, &ji, &jj);
    const auto fi = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return OdometryResidual(Eigen::Vector3d(x), xj, measured);
    };
    const auto fj = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return OdometryResidual(xi, Eigen::Vector3d(x), measured);
    };
    EXPECT_LT((ji - NumericalJacobian(fi, xi, {2})).cwiseAbs().maxCoeff(), kTolerance);
    EXPECT_LT((jj - NumericalJacobian(fj, xj, {2})).cwiseAbs().maxCoeff(), kTolerance);
  }
}

TEST_F(FactorJacobianTest, OdometryResidualIsZeroForTheExactMotion) {
  const Eigen::Vector3d xi(1.0, 2.0, 3.0);
  const Eigen::Vector3d measured(0.5, -0.2, 0.4);
  const Eigen::Vector3d xj = ComposePoses(xi, measured);
  EXPECT_LT(OdometryResidual(xi, xj, measured).norm(), 1e-14);
}

TEST_F(FactorJacobianTest, RangeBearingMatchesNumerical) {
  const SensorMount mount{0.12, -0.05};
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d pose = RandomPose();
    const Eigen::Vector2d point = RandomPoint();
    const Eigen::Vector2d measured(5.0, 0.3);
    Eigen::Matrix<double, 2, 3> jp;
    Eigen::Matrix2d jl;
    RangeBearingResidual(pose, point, measured, mount, &jp, &jl);
    const auto fp = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return RangeBearingResidual(Eigen::Vector3d(x), point, measured, mount);
    };
    const auto fl = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return RangeBearingResidual(pose, Eigen::Vector2d(x), measured, mount);
    };
    EXPECT_LT((jp - NumericalJacobian(fp, pose, {1})).cwiseAbs().maxCoeff(), kTolerance);
    EXPECT_LT((jl - NumericalJacobian(fl, point, {1})).cwiseAbs().maxCoeff(), kTolerance);
  }
}

TEST_F(FactorJacobianTest, RangeBearingIsEquations10And11) {
  // Robot at (1, 2) facing +y, laser 0.5 m forward: the sensor is at (1, 2.5); a point at
  // (1, 5.5) is 3 m straight ahead.
  const Eigen::Vector2d residual = RangeBearingResidual(
      Eigen::Vector3d(1, 2, M_PI / 2), Eigen::Vector2d(1, 5.5), Eigen::Vector2d(0, 0), {0.5, 0});
  EXPECT_NEAR(residual(0), 3.0, 1e-12);
  EXPECT_NEAR(residual(1), 0.0, 1e-12);
  // Bearing residuals wrap: predicted pi - 0.01 against measured -pi + 0.01 is -0.02.
  const Eigen::Vector2d wrapped =
      RangeBearingResidual(Eigen::Vector3d(0, 0, 0), Eigen::Vector2d(-1, std::tan(0.01)),
                           Eigen::Vector2d(0, -M_PI + 0.01), {});
  EXPECT_NEAR(wrapped(1), -0.02, 1e-9);
}

TEST_F(FactorJacobianTest, RelativePositionMatchesNumerical) {
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d pose = RandomPose();
    const Eigen::Vector2d point = RandomPoint();
    const Eigen::Vector2d measured = RandomPoint();
    Eigen::Matrix<double, 2, 3> jp;
    Eigen::Matrix2d jl;
    RelativePositionResidual(pose, point, measured, &jp, &jl);
    const auto fp = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return RelativePositionResidual(Eigen::Vector3d(x), point, measured);
    };
    const auto fl = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return RelativePositionResidual(pose, Eigen::Vector2d(x), measured);
    };
    EXPECT_LT((jp - NumericalJacobian(fp, pose)).cwiseAbs().maxCoeff(), kTolerance);
    EXPECT_LT((jl - NumericalJacobian(fl, point)).cwiseAbs().maxCoeff(), kTolerance);
  }
}

TEST_F(FactorJacobianTest, PriorsMatchNumerical) {
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d pose = RandomPose();
    const Eigen::Vector3d prior = ComposePoses(pose, RandomPose() * 0.05);
    Eigen::Matrix3d jacobian;
    PosePriorResidual(pose, prior, &jacobian);
    const auto f = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return PosePriorResidual(Eigen::Vector3d(x), prior);
    };
    EXPECT_LT((jacobian - NumericalJacobian(f, pose, {2})).cwiseAbs().maxCoeff(), kTolerance);
    const Eigen::Vector2d point = RandomPoint();
    Eigen::Matrix2d point_jacobian;
    PointPriorResidual(point, Eigen::Vector2d(1, 2), &point_jacobian);
    const auto g = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return PointPriorResidual(Eigen::Vector2d(x), Eigen::Vector2d(1, 2));
    };
    EXPECT_LT((point_jacobian - NumericalJacobian(g, point)).cwiseAbs().maxCoeff(), kTolerance);
  }
}

TEST(SquareRootInformationTest, RefusesWhatIsNotAnInformationMatrix) {
  Eigen::Matrix2d root;
  EXPECT_FALSE(SquareRootInformation<2>(Eigen::Matrix2d::Identity() * 4.0, &root));
  EXPECT_LT((root - 2.0 * Eigen::Matrix2d::Identity()).norm(), 1e-15);
  Eigen::Matrix2d bad;
  bad << 1, 0.5, 0.4, 1;
  EXPECT_TRUE(SquareRootInformation<2>(bad, &root));  // asymmetric
  bad << 1, 2, 2, 1;
  EXPECT_TRUE(SquareRootInformation<2>(bad, &root));  // indefinite
  bad << 1, 0, 0, 0;
  EXPECT_TRUE(SquareRootInformation<2>(bad, &root));  // singular
  bad << NAN, 0, 0, 1;
  EXPECT_TRUE(SquareRootInformation<2>(bad, &root));
  EXPECT_TRUE(SquareRootInformation<3>(Eigen::Matrix3d::Zero(), nullptr));
}

}  // namespace
}  // namespace slammtt
