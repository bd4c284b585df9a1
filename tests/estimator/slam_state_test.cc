// The state's block operations against dense reference computations.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "estimator/constant_velocity_model.h"
#include "estimator/ekf_prediction.h"
#include "estimator/slam_state.h"

namespace slammtt {
namespace {

constexpr int kR = SlamState::kRobotDim;  // robot block: pose + heading drift

// A state with random correlated covariance: robot (pose and heading drift), 3 landmarks,
// 2 movers.
SlamState RandomState(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  SlamState state(Eigen::Vector3d(0.1, -0.2, 0.3), 0.01 * Eigen::Matrix3d::Identity(), 1e-4);
  state.mean()(SlamState::kHeadingDriftIndex) = 0.012;
  for (int k = 0; k < 5; ++k) {
    Eigen::Matrix<double, 2, 3> g;
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 3; ++c) g(r, c) = normal(rng);
    }
    ObjectRecord record;
    record.id = k + 1;
    const int j = state.AddObject(Eigen::Vector2d(normal(rng), normal(rng)) * 5.0, g,
                                  0.04 * Eigen::Matrix2d::Identity(), record);
    if (k >= 3) state.AddVelocity(j, Eigen::Vector2d(0.5, -0.25), 0.3 * Eigen::Matrix2d::Identity());
  }
  // Mix everything with a random full-rank transform so every block is correlated.
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(state.dim(), state.dim());
  for (int r = 0; r < state.dim(); ++r) {
    for (int c = 0; c < state.dim(); ++c) a(r, c) += 0.1 * normal(rng);
  }
  const Eigen::MatrixXd p = a * state.covariance() * a.transpose() +
                            1e-3 * Eigen::MatrixXd::Identity(state.dim(), state.dim());
  state.covariance() = 0.5 * (p + p.transpose());
  return state;
}

TEST(SlamStateTest, StartsWithAnIndependentHeadingDrift) {
  SlamState state(Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d(0.1, 0.2, 0.05).asDiagonal(),
                  2.5e-5);
  EXPECT_EQ(state.dim(), kR);
  EXPECT_EQ(state.heading_drift_rad_per_m(), 0.0);
  EXPECT_EQ(state.heading_drift_variance(), 2.5e-5);
  EXPECT_TRUE((state.covariance().block<3, 1>(0, 3).isZero()));
  EXPECT_TRUE((state.covariance().block<1, 3>(3, 0).isZero()));
  EXPECT_EQ(state.robot_covariance(), Eigen::Matrix3d(Eigen::Vector3d(0.1, 0.2, 0.05).asDiagonal()));
}

TEST(SlamStateTest, AddObjectCorrelatesThroughTheRobot) {
  SlamState state = RandomState(7);
  state.RemoveObjects({0, 1, 2, 3, 4});
  ASSERT_EQ(state.dim(), kR);
  Eigen::Matrix<double, 2, 3> g;
  g << 1.0, 0.0, -2.0, 0.0, 1.0, 3.0;
  const Eigen::Matrix2d c = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  const int j = state.AddObject(Eigen::Vector2d(3.0, 2.0), g, c, ObjectRecord{});
  EXPECT_EQ(j, 0);
  EXPECT_EQ(state.dim(), kR + 2);
  const Eigen::Matrix3d prr = state.robot_covariance();
  // The point inherits the pose's correlation with the heading drift: P_p,b = G P_pose,b.
  const Eigen::Matrix<double, 3, 4> p_pose_robot = state.covariance().block<3, 4>(0, 0);
  ASSERT_NE(p_pose_robot(0, 3), 0.0);
  EXPECT_TRUE((state.covariance().block<2, 2>(kR, kR).isApprox(g * prr * g.transpose() + c)));
  EXPECT_TRUE((state.covariance().block<2, 4>(kR, 0).isApprox(g * p_pose_robot)));
  EXPECT_TRUE((state.covariance().block<4, 2>(0, kR).isApprox((g * p_pose_robot).transpose())));
  EXPECT_FALSE(state.object(0).has_velocity());
}

TEST(SlamStateTest, GrowsPastItsInitialCapacity) {
  SlamState state(Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity());
  Eigen::Matrix<double, 2, 3> g = Eigen::Matrix<double, 2, 3>::Zero();
  g(0, 0) = 1.0;
  g(1, 1) = 1.0;
  for (int k = 0; k < 100; ++k) {
    const int j = state.AddObject(Eigen::Vector2d(k, -k), g, Eigen::Matrix2d::Identity(), {});
    state.AddVelocity(j, Eigen::Vector2d(k, 0.0), Eigen::Matrix2d::Identity());
  }
  EXPECT_EQ(state.dim(), kR + 400);
  EXPECT_EQ(state.position(57), Eigen::Vector2d(57, -57));
  EXPECT_EQ(state.velocity(99), Eigen::Vector2d(99, 0));
  EXPECT_DOUBLE_EQ(state.covariance()(kR, 0), 0.01);
  EXPECT_TRUE(state.covariance().isApprox(state.covariance().transpose()));
}

TEST(SlamStateTest, RemovingObjectsKeepsTheOtherBlocks) {
  SlamState state = RandomState(1);
  const Eigen::MatrixXd p = state.covariance();
  const Eigen::VectorXd x = state.mean();
  const int p3 = state.object(3).position_index;
  const int v3 = state.object(3).velocity_index;
  state.RemoveObjects({1, 4, 1});
  ASSERT_EQ(state.num_objects(), 3);
  EXPECT_EQ(state.dim(), kR + 2 + 2 + 4);
  EXPECT_EQ(state.object(2).record.id, 4);
  // The mover that stayed (old object 3) keeps its mean and its blocks with the robot.
  const int np = state.object(2).position_index;
  const int nv = state.object(2).velocity_index;
  EXPECT_EQ(state.mean().segment<2>(np), x.segment<2>(p3));
  EXPECT_EQ(state.mean().segment<2>(nv), x.segment<2>(v3));
  EXPECT_EQ(Eigen::Matrix2d(state.covariance().block(np, nv, 2, 2)), Eigen::Matrix2d(p.block(p3, v3, 2, 2)));
  EXPECT_EQ(Eigen::MatrixXd(state.covariance().block(0, np, kR, 2)), Eigen::MatrixXd(p.block(0, p3, kR, 2)));
  EXPECT_EQ(Eigen::Matrix4d(state.covariance().topLeftCorner(kR, kR)), Eigen::Matrix4d(p.topLeftCorner(kR, kR)));
  EXPECT_TRUE(state.covariance().isApprox(state.covariance().transpose()));
}

TEST(SlamStateTest, RemovingVelocityConditionsOnZeroThenMarginalises) {
  SlamState state = RandomState(2);
  const Eigen::MatrixXd p = state.covariance();
  const Eigen::VectorXd x = state.mean();
  const int v = state.object(3).velocity_index;
  // Reference: condition on x_v = 0 exactly (dense), then drop v.
  const Eigen::MatrixXd p_xv = p.middleCols(v, 2);
  const Eigen::Matrix2d p_vv = p.block<2, 2>(v, v);
  const Eigen::VectorXd x_conditioned = x - p_xv * p_vv.inverse() * x.segment<2>(v);
  const Eigen::MatrixXd p_conditioned = p - p_xv * p_vv.inverse() * p_xv.transpose();
  std::vector<int> keep;
  for (int i = 0; i < state.dim(); ++i) {
    if (i != v && i != v + 1) keep.push_back(i);
  }
  state.RemoveVelocityAssumingZero(3);
  EXPECT_FALSE(state.object(3).has_velocity());
  ASSERT_EQ(state.dim(), static_cast<int>(keep.size()));
  for (int r = 0; r < state.dim(); ++r) {
    EXPECT_NEAR(state.mean()(r), x_conditioned(keep[static_cast<size_t>(r)]), 1e-12);
    for (int c = 0; c < state.dim(); ++c) {
      EXPECT_NEAR(state.covariance()(r, c),
                  p_conditioned(keep[static_cast<size_t>(r)], keep[static_cast<size_t>(c)]), 1e-12);
    }
  }
  EXPECT_EQ(state.covariance(), state.covariance().transpose());
}

TEST(SlamStateTest, AStationaryAnchorIsAPerfectlyCorrelatedCopyOfThePosition) {
  SlamState state = RandomState(3);
  const Eigen::MatrixXd p = state.covariance();
  const int n = state.dim();
  const int pos = state.object(3).position_index;
  state.AddStationaryAnchor(3);
  state.AddStationaryAnchor(3);  // no-op: it has one
  ASSERT_TRUE(state.object(3).has_anchor());
  const int a = state.object(3).anchor_index;
  EXPECT_EQ(state.dim(), n + 2);
  EXPECT_EQ(a, n);
  EXPECT_EQ(Eigen::Vector2d(state.mean().segment<2>(a)), state.position(3));
  EXPECT_EQ(Eigen::MatrixXd(state.covariance().block(a, 0, 2, n)),
            Eigen::MatrixXd(p.block(pos, 0, 2, n)));
  EXPECT_EQ(Eigen::Matrix2d(state.covariance().block<2, 2>(a, a)),
            Eigen::Matrix2d(p.block<2, 2>(pos, pos)));
  EXPECT_EQ(state.covariance(), state.covariance().transpose());
  // The difference position - anchor is known exactly: zero mean, zero covariance.
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, state.dim());
  h.block<2, 2>(0, pos).setIdentity();
  h.block<2, 2>(0, a) = -Eigen::Matrix2d::Identity();
  EXPECT_NEAR((h * state.covariance() * h.transpose()).norm(), 0.0, 1e-12);
  // Removing another object keeps the anchor on its own slots; removing its object removes it.
  state.AddStationaryAnchor(4);
  const Eigen::Vector2d anchor4 = state.mean().segment<2>(state.object(4).anchor_index);
  state.RemoveObjects({3});
  ASSERT_TRUE(state.object(3).has_anchor());  // old object 4
  EXPECT_EQ(Eigen::Vector2d(state.mean().segment<2>(state.object(3).anchor_index)), anchor4);
  EXPECT_EQ(state.dim(), n + 4 - 6);  // two anchors added, position, velocity and anchor gone
  state.RemoveAnchor(3);
  EXPECT_FALSE(state.object(3).has_anchor());
  EXPECT_EQ(state.dim(), n - 4);
}

// Starting an object again (new_objects.h: RestartObjectsBesideBirths) gives it what AddObject
// and AddVelocity give a new object, in its own slots: the position correlated with everything
// only through the robot, the velocity at zero and independent, the anchor a fresh copy.
TEST(SlamStateTest, RestartingAnObjectGivesItTheStateOfANewOne) {
  SlamState state = RandomState(11);
  state.AddStationaryAnchor(3);
  const int n = state.dim();
  const int pos = state.object(3).position_index;
  const int vel = state.object(3).velocity_index;
  const int anchor = state.object(3).anchor_index;
  const Eigen::MatrixXd before = state.covariance();
  const Eigen::VectorXd mean_before = state.mean();
  Eigen::Matrix<double, 2, 3> g;
  g << 1.0, 0.0, -2.0, 0.0, 1.0, 3.0;
  const Eigen::Matrix2d c = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  const Eigen::Matrix2d velocity_prior = 2.0 * Eigen::Matrix2d::Identity();
  state.RestartObject(3, Eigen::Vector2d(7.0, -1.0), g, c, velocity_prior);
  ASSERT_EQ(state.dim(), n);
  const Eigen::MatrixXd after = state.covariance();
  EXPECT_EQ(state.position(3), Eigen::Vector2d(7.0, -1.0));
  EXPECT_EQ(state.velocity(3), Eigen::Vector2d::Zero());
  EXPECT_EQ(Eigen::Vector2d(state.mean().segment<2>(anchor)), Eigen::Vector2d(7.0, -1.0));
  EXPECT_EQ(state.object(3).first_estimate_m, Eigen::Vector2d(7.0, -1.0));
  const Eigen::Matrix<double, 3, Eigen::Dynamic> pose_rows = before.topRows(3);
  // Against every other state (robot, heading drift, the other objects): G P_pose,x.
  for (int x = 0; x < n; ++x) {
    if ((x >= pos && x < pos + 2) || (x >= vel && x < vel + 2) ||
        (x >= anchor && x < anchor + 2)) {
      continue;
    }
    EXPECT_TRUE((after.block<2, 1>(pos, x).isApprox(g * pose_rows.col(x), 1e-12))) << x;
    EXPECT_TRUE((after.block<2, 1>(vel, x).isZero())) << x;
    EXPECT_TRUE((after.block<2, 1>(anchor, x).isApprox(after.block<2, 1>(pos, x)))) << x;
    // The other states keep their mean and covariance.
    EXPECT_EQ(state.mean()(x), mean_before(x));
    for (int y = 0; y < n; ++y) {
      if ((y >= pos && y < pos + 2) || (y >= vel && y < vel + 2) ||
          (y >= anchor && y < anchor + 2)) {
        continue;
      }
      EXPECT_EQ(after(x, y), before(x, y));
    }
  }
  const Eigen::Matrix2d own = g * before.topLeftCorner<3, 3>() * g.transpose() + c;
  EXPECT_TRUE((after.block<2, 2>(pos, pos).isApprox(own)));
  EXPECT_TRUE((after.block<2, 2>(anchor, anchor).isApprox(own)));
  EXPECT_TRUE((after.block<2, 2>(pos, anchor).isApprox(own)));
  EXPECT_EQ(Eigen::Matrix2d(after.block<2, 2>(vel, vel)), velocity_prior);
  EXPECT_TRUE((after.block<2, 2>(pos, vel).isZero()));
  EXPECT_EQ(after, after.transpose());
  // Still a covariance.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(after);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12);
}

// The state after an object with an anchor moved for dt (eq. 6 with the process noise of eq. 8):
// its position and its anchor differ.
SlamState AnchoredAndMoved(uint64_t seed, double dt_s) {
  SlamState state = RandomState(seed);
  state.AddStationaryAnchor(3);
  const int p = state.object(3).position_index;
  const int v = state.object(3).velocity_index;
  PredictConstantVelocityInPlace(dt_s, p, v, state.mean(), state.covariance());
  state.MirrorRowToColumn(p);
  state.MirrorRowToColumn(p + 1);
  state.covariance().block<2, 2>(v, v) += 0.04 * dt_s * Eigen::Matrix2d::Identity();
  return state;
}

TEST(SlamStateTest, ConditioningOnTheAnchorIsThePerfectDisplacementMeasurementThenDropsIt) {
  SlamState state = AnchoredAndMoved(4, 0.5);
  const Eigen::MatrixXd p = state.covariance();
  const Eigen::VectorXd x = state.mean();
  const int pos = state.object(3).position_index;
  const int a = state.object(3).anchor_index;
  // Reference: the dense Kalman update with the perfect measurement position - anchor = 0.
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, state.dim());
  h.block<2, 2>(0, pos).setIdentity();
  h.block<2, 2>(0, a) = -Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d s = h * p * h.transpose();
  const Eigen::Vector2d d = h * x;
  ASSERT_GT(d.norm(), 0.1);
  const double nis = d.dot(s.inverse() * d);
  const Eigen::MatrixXd gain = p * h.transpose() * s.inverse();
  const Eigen::VectorXd x_conditioned = x - gain * d;
  const Eigen::MatrixXd p_conditioned = p - gain * h * p;
  std::vector<int> keep;
  for (int i = 0; i < state.dim(); ++i) {
    if (i != a && i != a + 1) keep.push_back(i);
  }
  // A gate below the displacement's NIS: the object moved, only the anchor is dropped.
  SlamState moved = state;
  EXPECT_FALSE(moved.ConditionOnAnchorAndRemoveIt(3, 0.5 * nis));
  EXPECT_FALSE(moved.object(3).has_anchor());
  ASSERT_EQ(moved.dim(), static_cast<int>(keep.size()));
  for (int r = 0; r < moved.dim(); ++r) {
    EXPECT_EQ(moved.mean()(r), x(keep[static_cast<size_t>(r)]));
  }
  EXPECT_TRUE(state.ConditionOnAnchorAndRemoveIt(3, 2.0 * nis));
  EXPECT_FALSE(state.object(3).has_anchor());
  ASSERT_EQ(state.dim(), static_cast<int>(keep.size()));
  for (int r = 0; r < state.dim(); ++r) {
    EXPECT_NEAR(state.mean()(r), x_conditioned(keep[static_cast<size_t>(r)]), 1e-10);
    for (int c = 0; c < state.dim(); ++c) {
      EXPECT_NEAR(state.covariance()(r, c),
                  p_conditioned(keep[static_cast<size_t>(r)], keep[static_cast<size_t>(c)]),
                  1e-10);
    }
  }
  EXPECT_EQ(state.covariance(), state.covariance().transpose());
  // Without an anchor nothing happens.
  const Eigen::VectorXd before = state.mean();
  EXPECT_FALSE(state.ConditionOnAnchorAndRemoveIt(3, 1e9));
  EXPECT_EQ(Eigen::VectorXd(state.mean()), before);
}

TEST(EkfPredictionTest, BlockPredictionEqualsDenseEquationNine) {
  SlamState state = RandomState(3);
  const Eigen::MatrixXd p = state.covariance();
  const Eigen::VectorXd x = state.mean();
  const double dt = 0.125;
  const double sigma_q = 0.7;
  Eigen::Matrix4d f;
  f << 1.0, 0.0, -0.2, -0.04,  //
      0.0, 1.0, 0.3, 0.06,     //
      0.0, 0.0, 1.0, 0.2,      //
      0.0, 0.0, 0.0, 1.0;
  const Eigen::Matrix4d q_robot = Eigen::Vector4d(1e-3, 2e-3, 5e-4, 1e-8).asDiagonal();
  const Eigen::Vector3d new_pose(0.4, -0.1, 0.35);
  // Dense reference: F_full = blkdiag(F, I, T) per eq. 9, Q_full on robot and movers.
  const int n = state.dim();
  Eigen::MatrixXd f_full = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd q_full = Eigen::MatrixXd::Zero(n, n);
  f_full.topLeftCorner<kR, kR>() = f;
  q_full.topLeftCorner<kR, kR>() = q_robot;
  Eigen::VectorXd x_expected = x;
  x_expected.head<3>() = new_pose;
  const Eigen::Matrix4d q_mover = ConstantVelocityProcessNoise(dt, sigma_q);
  for (const StateObject& o : state.objects()) {
    if (!o.has_velocity()) continue;
    const int idx[4] = {o.position_index, o.position_index + 1, o.velocity_index,
                        o.velocity_index + 1};
    f_full(idx[0], idx[2]) = dt;
    f_full(idx[1], idx[3]) = dt;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) q_full(idx[r], idx[c]) = q_mover(r, c);
    }
    x_expected(idx[0]) += dt * x(idx[2]);
    x_expected(idx[1]) += dt * x(idx[3]);
  }
  const Eigen::MatrixXd expected = f_full * p * f_full.transpose() + q_full;
  ApplyRobotPrediction(new_pose, f, q_robot, &state);
  PredictMovers(dt, sigma_q, sigma_q, sigma_q, &state);
  EXPECT_LT((state.covariance() - expected).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((state.mean() - x_expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EkfPredictionTest, AccumulatedOdometryEqualsStepByStepPrediction) {
  SlamState stepwise = RandomState(4);
  SlamState composed = stepwise;
  const std::vector<OdometryIncrement> steps = {{0.1, 0.02}, {0.12, -0.05}, {0.09, 0.3}};
  const Eigen::Matrix2d noise = Eigen::Vector2d(1e-4, 3e-4).asDiagonal();
  const double walk_var_per_m = 1e-6;
  RobotMotionAccumulator accumulator(composed.robot_pose(), composed.heading_drift_rad_per_m(),
                                     walk_var_per_m);
  for (const OdometryIncrement& u : steps) {
    Eigen::Matrix4d f;
    Eigen::Matrix<double, 4, 2> g;
    const Eigen::Vector3d pose = PredictRobotPoseWithHeadingDrift(
        stepwise.robot_pose(), stepwise.heading_drift_rad_per_m(), u, &f, &g);
    Eigen::Matrix4d q = g * noise * g.transpose();
    q(3, 3) += walk_var_per_m * std::abs(u.distance_m);
    ApplyRobotPrediction(pose, f, q, &stepwise);
    accumulator.Add(u, noise);
  }
  ApplyRobotPrediction(accumulator.pose(), accumulator.jacobian(), accumulator.noise(), &composed);
  EXPECT_LT((stepwise.covariance() - composed.covariance()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((stepwise.mean() - composed.mean()).cwiseAbs().maxCoeff(), 1e-12);
  // The drift moved the pose: without it the same steps end elsewhere.
  EXPECT_NE(composed.heading_drift_rad_per_m(), 0.0);
  RobotMotionAccumulator no_drift(RandomState(4).robot_pose());
  for (const OdometryIncrement& u : steps) no_drift.Add(u, noise);
  EXPECT_GT(std::abs(no_drift.pose()(2) - composed.robot_pose()(2)), 0.012 * 0.3);
}

}  // namespace
}  // namespace slammtt
