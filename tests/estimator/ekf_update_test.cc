// The grouped Cholesky-form update against the textbook dense EKF update (paper eq. 22 in
// Joseph form), and its symmetry / positive semi-definiteness over long runs.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "estimator/angle.h"
#include "estimator/ekf_prediction.h"
#include "estimator/ekf_update.h"

namespace slammtt {
namespace {

SlamState StateWithObjects(int count, double spread_m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-spread_m, spread_m);
  SlamState state(Eigen::Vector3d(0.0, 0.0, 0.2), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  for (int k = 0; k < count; ++k) {
    Eigen::Matrix<double, 2, 3> g;
    g << 1.0, 0.0, 0.5, 0.0, 1.0, -0.3;
    ObjectRecord record;
    record.id = k + 1;
    const int j = state.AddObject(Eigen::Vector2d(uniform(rng) + 2.0 * spread_m, uniform(rng)), g,
                                  0.05 * Eigen::Matrix2d::Identity(), record);
    if (k % 3 == 0) state.AddVelocity(j, Eigen::Vector2d(0.3, 0.1), 0.5 * Eigen::Matrix2d::Identity());
  }
  return state;
}

// Dense reference: stacked H over all observations, Joseph-form eq. 22.
void DenseUpdate(const std::vector<ObjectObservation>& observations, const SensorMount& mount,
                 SlamState* state) {
  const int n = state->dim();
  const int m = 2 * static_cast<int>(observations.size());
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m, n);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd nu(m);
  for (size_t t = 0; t < observations.size(); ++t) {
    const ObjectObservation& o = observations[t];
    Eigen::Matrix<double, 2, 3> hr;
    Eigen::Matrix2d hp;
    const Eigen::Vector2d z =
        PredictRangeBearing(state->robot_pose(), state->position(o.object), mount, &hr, &hp);
    const int row = 2 * static_cast<int>(t);
    h.block<2, 3>(row, 0) = hr;
    h.block<2, 2>(row, state->object(o.object).position_index) = hp;
    r.block<2, 2>(row, row) = o.measurement.covariance;
    nu.segment<2>(row) = o.measurement.range_bearing - z;
    nu(row + 1) = WrapAngle(nu(row + 1));
  }
  const Eigen::MatrixXd p = state->covariance();
  const Eigen::MatrixXd s = h * p * h.transpose() + r;
  const Eigen::MatrixXd k = p * h.transpose() * s.inverse();
  const Eigen::MatrixXd i_kh = Eigen::MatrixXd::Identity(n, n) - k * h;
  state->covariance() = i_kh * p * i_kh.transpose() + k * r * k.transpose();
  state->mean() += k * nu;
}

std::vector<ObjectObservation> NoisyObservations(const SlamState& truth_state,
                                                 const std::vector<int>& objects,
                                                 const SensorMount& mount, std::mt19937_64* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<ObjectObservation> observations;
  for (int j : objects) {
    ObjectObservation o;
    o.object = j;
    o.measurement.covariance = Eigen::Vector2d(0.04, 0.0012).asDiagonal();
    o.measurement.range_bearing =
        PredictRangeBearing(truth_state.robot_pose(), truth_state.position(j), mount) +
        Eigen::Vector2d(0.2 * normal(*rng), 0.035 * normal(*rng));
    o.measurement.range_bearing(1) = WrapAngle(o.measurement.range_bearing(1));
    observations.push_back(o);
  }
  return observations;
}

TEST(EkfUpdateTest, OneGroupEqualsTheDenseJosephFormUpdate) {
  const SensorMount mount{0.1, 0.05};
  SlamState state = StateWithObjects(12, 4.0, 1);
  std::mt19937_64 rng(7);
  const std::vector<ObjectObservation> observations =
      NoisyObservations(state, {0, 2, 3, 5, 7, 8, 11}, mount, &rng);
  SlamState reference = state;
  DenseUpdate(observations, mount, &reference);
  const UpdateStats stats = ApplyObservations(observations, mount,
                                              std::numeric_limits<double>::infinity(), 100, &state);
  EXPECT_EQ(stats.applied, 7);
  EXPECT_EQ(stats.failed, 0);
  EXPECT_LT((state.covariance() - reference.covariance()).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::VectorXd difference = state.mean() - reference.mean();
  difference(2) = WrapAngle(difference(2));
  EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-12);
  // Symmetric bit for bit.
  EXPECT_EQ(state.covariance(), state.covariance().transpose());
}

TEST(EkfUpdateTest, SequentialGroupsAgreeWithOneBatchToFirstOrder) {
  const SensorMount mount;
  SlamState batch = StateWithObjects(10, 3.0, 2);
  SlamState grouped = batch;
  std::mt19937_64 rng(8);
  const std::vector<ObjectObservation> observations =
      NoisyObservations(batch, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, mount, &rng);
  ApplyObservations(observations, mount, std::numeric_limits<double>::infinity(), 100, &batch);
  ApplyObservations(observations, mount, std::numeric_limits<double>::infinity(), 3, &grouped);
  // They differ only through relinearisation between groups.
  EXPECT_LT((batch.covariance() - grouped.covariance()).cwiseAbs().maxCoeff(), 2e-3);
  EXPECT_LT((batch.mean() - grouped.mean()).head<2>().norm(), 0.05);
}

TEST(EkfUpdateTest, GateSkipsIncompatibleObservations) {
  const SensorMount mount;
  SlamState state = StateWithObjects(4, 3.0, 3);
  std::vector<ObjectObservation> observations(2);
  observations[0].object = 0;
  observations[0].measurement.covariance = Eigen::Vector2d(0.04, 0.0012).asDiagonal();
  observations[0].measurement.range_bearing =
      PredictRangeBearing(state.robot_pose(), state.position(0), mount);
  observations[1] = observations[0];
  observations[1].object = 1;
  observations[1].measurement.range_bearing =
      PredictRangeBearing(state.robot_pose(), state.position(1), mount) + Eigen::Vector2d(25.0, 0);
  const SlamState before = state;
  const UpdateStats stats = ApplyObservations(observations, mount, 9.21, 8, &state);
  EXPECT_EQ(stats.applied, 1);
  EXPECT_EQ(stats.gated_out, 1);
  EXPECT_LT(state.covariance()(state.object(0).position_index, state.object(0).position_index),
            before.covariance()(before.object(0).position_index, before.object(0).position_index));
}

TEST(EkfUpdateTest, ObjectAtTheSensorIsReportedNotApplied) {
  const SensorMount mount;
  SlamState state(Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity());
  state.AddObject(Eigen::Vector2d::Zero(), Eigen::Matrix<double, 2, 3>::Zero(),
                  Eigen::Matrix2d::Identity(), ObjectRecord{});
  ObjectObservation o;
  o.object = 0;
  o.measurement.range_bearing = Eigen::Vector2d(1.0, 0.0);
  const UpdateStats stats =
      ApplyObservations({o}, mount, std::numeric_limits<double>::infinity(), 8, &state);
  EXPECT_EQ(stats.applied, 0);
  EXPECT_EQ(stats.failed, 1);
  EXPECT_TRUE(state.mean().allFinite());
}

// Thousands of predict/update cycles with a moving robot, landmarks and movers: the covariance
// stays symmetric, finite and positive semi-definite.
TEST(EkfUpdateTest, CovarianceStaysSymmetricPositiveSemiDefiniteOverLongRuns) {
  const SensorMount mount{0.2, 0.0};
  SlamState state = StateWithObjects(30, 6.0, 4);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Matrix2d odometry_noise = Eigen::Vector2d(1e-4, 4e-4).asDiagonal();
  for (int step = 0; step < 3000; ++step) {
    Eigen::Matrix3d f;
    Eigen::Matrix<double, 3, 2> g;
    const OdometryIncrement u{0.05, 0.01 * std::sin(step * 0.01)};
    const Eigen::Vector3d pose = PredictRobotPose(state.robot_pose(), u, &f, &g);
    ApplyRobotPrediction(pose, f, g * odometry_noise * g.transpose(), &state);
    PredictMovers(0.1, 0.5, 0.5, 0.5, &state);
    std::vector<int> seen;
    for (int j = 0; j < state.num_objects(); ++j) {
      if ((step + j) % 2 == 0) seen.push_back(j);
    }
    ApplyObservations(NoisyObservations(state, seen, mount, &rng), mount, 1e6, 8, &state);
    if (step % 500 == 499) {
      const Eigen::MatrixXd p = state.covariance();
      ASSERT_TRUE(p.allFinite());
      ASSERT_TRUE(state.mean().allFinite());
      ASSERT_EQ(p, p.transpose());
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(p);
      EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-12 * p.trace()) << "step " << step;
    }
  }
}

}  // namespace
}  // namespace slammtt
