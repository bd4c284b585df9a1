// The smoother on small problems: known optima, batch against incremental, Gauss-Newton against
// Levenberg-Marquardt, marginals against a dense inverse, bad input, determinism.
#include "smoother/smoother.h"
#include "smoother/sparse_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/angle.h"
#include "smoother/factors.h"
#include "geometry/pose2.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

// A loop: poses on a circle of radius 5 m (the last odometry closes it back to pose 0),
// landmarks inside and outside it, each seen by range and bearing (laser mount (0.1, 0.05))
// from the poses within 6 m, and by relative position from every third pose.
struct LoopProblem {
  std::vector<Eigen::Vector3d> poses;
  std::vector<Eigen::Vector2d> landmarks;
  struct Odometry {
    int from, to;
    Eigen::Vector3d relative;
  };
  struct Observation {
    int pose, landmark;
    Eigen::Vector2d value;
    bool range_bearing;
  };
  std::vector<Odometry> odometry;
  std::vector<Observation> observations;
  Eigen::Matrix3d odometry_information = Eigen::Vector3d(400, 400, 2500).asDiagonal();
  Eigen::Matrix2d range_bearing_information = Eigen::Vector2d(100, 900).asDiagonal();
  Eigen::Matrix2d position_information;
  Eigen::Matrix3d prior_information = Eigen::Matrix3d::Identity() * 1e6;
  SensorMount mount{0.1, 0.05};

  // noise_scale 0: measurements exact, optimum = truth with chi^2 = 0.
  LoopProblem(int num_poses, double noise_scale, uint64_t seed) {
    position_information << 50, 10, 10, 80;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    for (int k = 0; k < num_poses; ++k) {
      const double angle = 2.0 * M_PI * k / num_poses;
      poses.emplace_back(5.0 * std::cos(angle), 5.0 * std::sin(angle), WrapAngle(angle + M_PI / 2));
    }
    for (int k = 0; k < 8; ++k) {
      const double angle = 2.0 * M_PI * (k + 0.5) / 8;
      const double radius = k % 2 == 0 ? 2.5 : 7.5;
      landmarks.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    }
    const auto noise3 = [&](const Eigen::Matrix3d& information) {
      const Eigen::Vector3d sigma = information.diagonal().cwiseSqrt().cwiseInverse();
      return Eigen::Vector3d(sigma(0) * gauss(rng), sigma(1) * gauss(rng), sigma(2) * gauss(rng));
    };
    for (int k = 0; k < num_poses; ++k) {
      const int next = (k + 1) % num_poses;
      Eigen::Vector3d relative = PoseBetween(poses[k], poses[next]);
      relative += noise_scale * noise3(odometry_information);
      odometry.push_back({k, next, relative});
      for (int l = 0; l < static_cast<int>(landmarks.size()); ++l) {
        if ((landmarks[l] - poses[k].head<2>()).norm() > 6.0) continue;
        Eigen::Vector2d rb =
            RangeBearingResidual(poses[k], landmarks[l], Eigen::Vector2d::Zero(), mount);
        rb(0) += noise_scale * 0.1 * gauss(rng);
        rb(1) = WrapAngle(rb(1) + noise_scale * (1.0 / 30.0) * gauss(rng));
        observations.push_back({k, l, rb, true});
        if (k % 3 == 0) {
          Eigen::Vector2d local =
              RelativePositionResidual(poses[k], landmarks[l], Eigen::Vector2d::Zero());
          local += noise_scale * 0.15 * Eigen::Vector2d(gauss(rng), gauss(rng));
          observations.push_back({k, l, local, false});
        }
      }
    }
  }

  // Initial estimates off the truth by up to 0.3 m / 0.1 rad.
  Eigen::Vector3d InitialPose(int k) const {
    return poses[k] +
           Eigen::Vector3d(0.3 * std::sin(k), 0.3 * std::cos(2 * k), 0.1 * std::sin(3 * k));
  }
  Eigen::Vector2d InitialLandmark(int l) const {
    return landmarks[l] + Eigen::Vector2d(0.3 * std::cos(l), -0.3 * std::sin(l));
  }

  // Adds pose k with its odometry from k - 1 (the closing odometry with the last pose),
  // the prior on pose 0, its observations and the landmarks they first see.
  void AddKeyframe(int k, Smoother* smoother) const {
    ASSERT_FALSE(smoother->AddPose(k, InitialPose(k)));
    if (k == 0) {
      ASSERT_FALSE(smoother->AddPosePrior(0, poses[0], prior_information));
    } else {
      ASSERT_FALSE(smoother->AddOdometry(k - 1, k, odometry[k - 1].relative, odometry_information));
    }
    if (k == static_cast<int>(poses.size()) - 1) {
      ASSERT_FALSE(smoother->AddOdometry(k, 0, odometry[k].relative, odometry_information));
    }
    for (const Observation& o : observations) {
      if (o.pose != k) continue;
      if (!smoother->LandmarkEstimate(o.landmark)) {
        ASSERT_FALSE(smoother->AddLandmark(o.landmark, InitialLandmark(o.landmark)));
      }
      if (o.range_bearing) {
        ASSERT_FALSE(smoother->AddRangeBearing(k, o.landmark, o.value, range_bearing_information,
                                               mount));
      } else {
        ASSERT_FALSE(smoother->AddRelativePosition(k, o.landmark, o.value, position_information));
      }
    }
  }

  void AddAll(Smoother* smoother) const {
    for (int k = 0; k < static_cast<int>(poses.size()); ++k) AddKeyframe(k, smoother);
  }

  // Whitened residuals of every factor, stacked, at the state (poses, then landmarks): the
  // problem's cost as a dense function, for the dense reference of the marginals.
  Eigen::VectorXd StackedResiduals(const Eigen::VectorXd& state) const {
    const int np = static_cast<int>(poses.size());
    const auto pose = [&](int k) { return Eigen::Vector3d(state.segment<3>(3 * k)); };
    const auto point = [&](int l) { return Eigen::Vector2d(state.segment<2>(3 * np + 2 * l)); };
    std::vector<double> out;
    const auto push = [&](const Eigen::VectorXd& r, const Eigen::MatrixXd& information) {
      const Eigen::MatrixXd upper = information.llt().matrixU();
      const Eigen::VectorXd w = upper * r;
      out.insert(out.end(), w.data(), w.data() + w.size());
    };
    push(PosePriorResidual(pose(0), poses[0]), prior_information);
    for (const Odometry& o : odometry) {
      push(OdometryResidual(pose(o.from), pose(o.to), o.relative), odometry_information);
    }
    for (const Observation& o : observations) {
      if (o.range_bearing) {
        push(RangeBearingResidual(pose(o.pose), point(o.landmark), o.value, mount),
             range_bearing_information);
      } else {
        push(RelativePositionResidual(pose(o.pose), point(o.landmark), o.value),
             position_information);
      }
    }
    return Eigen::Map<Eigen::VectorXd>(out.data(), out.size());
  }
};

Eigen::VectorXd State(const Smoother& smoother, const LoopProblem& problem) {
  const int np = static_cast<int>(problem.poses.size());
  Eigen::VectorXd state(3 * np + 2 * problem.landmarks.size());
  for (int k = 0; k < np; ++k) state.segment<3>(3 * k) = *smoother.PoseEstimate(k);
  for (int l = 0; l < static_cast<int>(problem.landmarks.size()); ++l) {
    state.segment<2>(3 * np + 2 * l) = *smoother.LandmarkEstimate(l);
  }
  return state;
}

double MaxStateDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int num_poses) {
  Eigen::VectorXd difference = a - b;
  for (int k = 0; k < num_poses; ++k) difference(3 * k + 2) = WrapAngle(difference(3 * k + 2));
  return difference.cwiseAbs().maxCoeff();
}

TEST(SmootherTest, ExactMeasurementsGiveTheTruthWithZeroChiSquare) {
  const LoopProblem problem(24, 0.0, 1);
  for (const auto method : {SmootherOptions::Method::kGaussNewton,
                            SmootherOptions::Method::kLevenbergMarquardt}) {
    SmootherOptions options;
    options.method = method;
    Smoother smoother(options);
    problem.AddAll(&smoother);
    const SolveReport report = smoother.Optimize();
    ASSERT_TRUE(report.ok) << report.error;
    EXPECT_TRUE(report.converged);
    EXPECT_GT(report.initial_chi_square, 100.0);
    EXPECT_LT(report.chi_square, 1e-16);
    for (int k = 0; k < 24; ++k) {
      const Eigen::Vector3d error = *smoother.PoseEstimate(k) - problem.poses[k];
      EXPECT_LT(error.head<2>().norm(), 1e-9);
      EXPECT_LT(std::abs(WrapAngle(error(2))), 1e-9);
    }
    for (int l = 0; l < 8; ++l) {
      EXPECT_LT((*smoother.LandmarkEstimate(l) - problem.landmarks[l]).norm(), 1e-9);
    }
  }
}

TEST(SmootherTest, ConflictingPointPriorsMeetInTheMiddle) {
  // Priors at 0 and 1 with information 4 and 12: optimum at 0.75, chi^2 = 4 * 0.75^2 +
  // 12 * 0.25^2 = 3.
  Smoother smoother;
  ASSERT_FALSE(smoother.AddLandmark(7, Eigen::Vector2d(10, -3)));
  ASSERT_FALSE(smoother.AddPointPrior(7, Eigen::Vector2d(0, 0), Eigen::Matrix2d::Identity() * 4));
  ASSERT_FALSE(smoother.AddPointPrior(7, Eigen::Vector2d(1, 1), Eigen::Matrix2d::Identity() * 12));
  const SolveReport report = smoother.Optimize();
  ASSERT_TRUE(report.ok) << report.error;
  EXPECT_NEAR(report.chi_square, 6.0, 1e-12);  // 3 from each coordinate
  EXPECT_LT((*smoother.LandmarkEstimate(7) - Eigen::Vector2d(0.75, 0.75)).norm(), 1e-12);
  const Eigen::Matrix2d covariance = *smoother.LandmarkCovariance(7);
  EXPECT_LT((covariance - Eigen::Matrix2d::Identity() / 16.0).norm(), 1e-15);
}

TEST(SmootherTest, NoisyLoopGaussNewtonAndLevenbergMarquardtAgree) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const LoopProblem problem(30, 1.0, seed);
    SmootherOptions gauss_newton;
    gauss_newton.method = SmootherOptions::Method::kGaussNewton;
    Smoother gn(gauss_newton);
    Smoother lm;
    problem.AddAll(&gn);
    problem.AddAll(&lm);
    const SolveReport a = gn.Optimize();
    const SolveReport b = lm.Optimize();
    ASSERT_TRUE(a.ok && b.ok) << a.error << b.error;
    EXPECT_TRUE(a.converged && b.converged);
    // 30 odometry (3 rows) + observations: chi^2 of the order of the residual count.
    EXPECT_GT(a.chi_square, 1.0);
    EXPECT_NEAR(a.chi_square, b.chi_square, 1e-9 * a.chi_square) << "seed " << seed;
    EXPECT_LT(MaxStateDifference(State(gn, problem), State(lm, problem), 30), 1e-7);
    EXPECT_NEAR(a.chi_square, gn.ChiSquare(), 1e-12 * a.chi_square);
  }
}

TEST(SmootherTest, IncrementalReachesTheBatchOptimum) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const LoopProblem problem(60, 1.0, seed);
    Smoother batch;
    problem.AddAll(&batch);
    const SolveReport batch_report = batch.Optimize();
    ASSERT_TRUE(batch_report.ok) << batch_report.error;

    SmootherOptions options;
    options.relinearize_threshold = 1e-5;
    options.relinearize_skip = 1;
    options.full_relinearization_interval = 25;
    options.min_free_slots = 4;  // run out of slots, re-order, go on
    options.max_incremental_relinearizations = 1000;  // relinearise by rank updates too
    // Relinearising everything at every update is dearer by rank updates than afresh; this test
    // is about the rank updates, so the cost rule is off.
    options.max_update_work_share = 0.0;
    Smoother incremental(options);
    int refactorizations = 0;
    int incremental_updates = 0;
    SolveReport report;
    for (int k = 0; k < 60; ++k) {
      problem.AddKeyframe(k, &incremental);
      report = incremental.Update();
      ASSERT_TRUE(report.ok) << report.error;
      refactorizations += report.refactorized ? 1 : 0;
      incremental_updates += report.refactorized ? 0 : 1;
      EXPECT_NEAR(report.chi_square, incremental.ChiSquare(), 1e-12 * report.chi_square);
    }
    EXPECT_GT(incremental_updates, 30);  // most keyframes by rank updates
    EXPECT_GT(refactorizations, 2);      // schedule and slots
    // A few more Gauss-Newton steps at the end converge to the batch optimum.
    for (int extra = 0; extra < 5; ++extra) report = incremental.Update();
    ASSERT_TRUE(report.ok) << report.error;
    EXPECT_NEAR(report.chi_square, batch_report.chi_square, 1e-6 * batch_report.chi_square)
        << "seed " << seed;
    EXPECT_LT(MaxStateDifference(State(incremental, problem), State(batch, problem), 60), 1e-6);
  }
}

TEST(SmootherTest, MarginalsMatchTheDenseInverse) {
  const LoopProblem problem(20, 1.0, 3);
  for (const bool incremental : {false, true}) {
    // The incremental factor is J^T J at the linearisation points (ISAM2's marginals): with a
    // small relinearisation threshold they follow the estimate.
    SmootherOptions options;
    options.relinearize_threshold = 1e-9;
    options.relinearize_skip = 1;
    Smoother smoother(options);
    if (incremental) {
      for (int k = 0; k < 20; ++k) {
        problem.AddKeyframe(k, &smoother);
        ASSERT_TRUE(smoother.Update().ok);
      }
      for (int extra = 0; extra < 10; ++extra) ASSERT_TRUE(smoother.Update().ok);
    } else {
      problem.AddAll(&smoother);
      ASSERT_TRUE(smoother.Optimize().ok);
    }
    const Eigen::VectorXd state = State(smoother, problem);
    const auto residuals = [&](const Eigen::VectorXd& x) { return problem.StackedResiduals(x); };
    const Eigen::MatrixXd jacobian = testing::NumericalJacobian(residuals, state, {}, 1e-7);
    const Eigen::MatrixXd covariance = (jacobian.transpose() * jacobian).inverse();
    const Eigen::Matrix3d last_pose = *smoother.PoseCovariance(19);
    const Eigen::Matrix3d dense_pose = covariance.block<3, 3>(3 * 19, 3 * 19);
    EXPECT_LT((last_pose - dense_pose).norm(), 1e-4 * dense_pose.norm())
        << incremental << "\n" << last_pose << "\n" << dense_pose;
    std::vector<LandmarkId> ids;
    for (int l = 0; l < 8; ++l) ids.push_back(l);
    ids.push_back(99);  // unknown: nullopt
    const auto blocks = smoother.LandmarkCovariances(ids);
    ASSERT_EQ(blocks.size(), 9u);
    EXPECT_FALSE(blocks[8]);
    for (int l = 0; l < 8; ++l) {
      ASSERT_TRUE(blocks[l]);
      const Eigen::Matrix2d dense = covariance.block<2, 2>(60 + 2 * l, 60 + 2 * l);
      EXPECT_LT((*blocks[l] - dense).norm(), 1e-4 * dense.norm()) << "landmark " << l;
      EXPECT_LT((*smoother.LandmarkCovariance(l) - *blocks[l]).norm(), 1e-12 * dense.norm());
    }
  }
}

// GTSAM's Pose2 retraction (pose * exp(step)) is another chart of the same problem: the same
// optimum, batch and incremental, and the pose marginal back in (x, y, theta).
TEST(SmootherTest, ExponentialPoseUpdateReachesTheSameOptimumAndMarginals) {
  SmootherOptions exponential;
  exponential.pose_update = SmootherOptions::PoseUpdate::kExponential;
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const LoopProblem problem(30, 1.0, seed);
    Smoother additive_batch;
    Smoother exponential_batch(exponential);
    problem.AddAll(&additive_batch);
    problem.AddAll(&exponential_batch);
    const SolveReport a = additive_batch.Optimize();
    const SolveReport b = exponential_batch.Optimize();
    ASSERT_TRUE(a.ok && b.ok) << a.error << b.error;
    EXPECT_NEAR(a.chi_square, b.chi_square, 1e-9 * a.chi_square) << "seed " << seed;
    EXPECT_LT(MaxStateDifference(State(additive_batch, problem),
                                 State(exponential_batch, problem), 30),
              1e-7);
    const Eigen::Matrix3d pa = *additive_batch.PoseCovariance(29);
    const Eigen::Matrix3d pb = *exponential_batch.PoseCovariance(29);
    EXPECT_LT((pa - pb).norm(), 1e-6 * pa.norm()) << pa << "\n" << pb;

    SmootherOptions options = exponential;
    options.relinearize_threshold = 1e-5;
    options.relinearize_skip = 1;
    Smoother incremental(options);
    SolveReport report;
    for (int k = 0; k < 30; ++k) {
      problem.AddKeyframe(k, &incremental);
      report = incremental.Update();
      ASSERT_TRUE(report.ok) << report.error;
    }
    for (int extra = 0; extra < 5; ++extra) report = incremental.Update();
    EXPECT_NEAR(report.chi_square, a.chi_square, 1e-6 * a.chi_square) << "seed " << seed;
    EXPECT_LT(MaxStateDifference(State(incremental, problem), State(additive_batch, problem), 30),
              1e-6);
  }
}

TEST(SmootherTest, UpdatesWithoutChiSquareGiveTheSameEstimates) {
  const LoopProblem problem(40, 1.0, 6);
  SmootherOptions quiet_options;
  quiet_options.update_chi_square = false;
  Smoother reporting;
  Smoother quiet(quiet_options);
  for (int k = 0; k < 40; ++k) {
    problem.AddKeyframe(k, &reporting);
    problem.AddKeyframe(k, &quiet);
    const SolveReport a = reporting.Update();
    const SolveReport b = quiet.Update();
    ASSERT_TRUE(a.ok && b.ok) << a.error << b.error;
    EXPECT_TRUE(std::isfinite(a.chi_square));
    EXPECT_TRUE(std::isnan(b.chi_square));
    EXPECT_EQ(a.refactorized, b.refactorized);
  }
  EXPECT_EQ(MaxStateDifference(State(reporting, problem), State(quiet, problem), 40), 0.0);
  EXPECT_EQ(reporting.ChiSquare(), quiet.ChiSquare());
}

// The parts of the graph are followed as factors arrive, and found again after a removal: a
// landmark that was a pose's only link to the prior leaves that pose free.
TEST(SmootherTest, AnchoringFollowsAdditionsAndRemovals) {
  Smoother smoother;
  const Eigen::Matrix3d info3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix2d info2 = Eigen::Matrix2d::Identity();
  ASSERT_FALSE(smoother.AddPose(0, Eigen::Vector3d(0, 0, 0)));
  ASSERT_FALSE(smoother.AddPosePrior(0, Eigen::Vector3d::Zero(), info3));
  ASSERT_FALSE(smoother.AddPose(1, Eigen::Vector3d(1, 0, 0)));
  ASSERT_FALSE(smoother.AddLandmark(7, Eigen::Vector2d(2, 1)));
  ASSERT_FALSE(smoother.AddLandmark(8, Eigen::Vector2d(3, -1)));
  ASSERT_FALSE(smoother.AddRelativePosition(0, 7, Eigen::Vector2d(2, 1), info2));
  ASSERT_FALSE(smoother.AddRelativePosition(0, 8, Eigen::Vector2d(3, -1), info2));
  SolveReport report = smoother.Update();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.error.find("pose 1 is in a part of the graph without a prior"),
            std::string::npos)
      << report.error;
  // Landmark 7 links pose 1 (two sightings fix its position and heading) to the prior.
  ASSERT_FALSE(smoother.AddRelativePosition(1, 7, Eigen::Vector2d(1, 1), info2));
  ASSERT_FALSE(smoother.AddRelativePosition(1, 8, Eigen::Vector2d(2, -1), info2));
  report = smoother.Update();
  ASSERT_TRUE(report.ok) << report.error;
  ASSERT_FALSE(smoother.RemoveLandmark(7));
  ASSERT_FALSE(smoother.RemoveLandmark(8));
  report = smoother.Update();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.error.find("pose 1 is in a part"), std::string::npos) << report.error;
  ASSERT_FALSE(smoother.AddOdometry(0, 1, Eigen::Vector3d(1, 0, 0), info3));
  report = smoother.Update();
  EXPECT_TRUE(report.ok) << report.error;
  EXPECT_LT((*smoother.PoseEstimate(1) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-9);
  // Two parts without a prior joined stay one part without a prior, until it is linked.
  ASSERT_FALSE(smoother.AddPose(2, Eigen::Vector3d(2, 0, 0)));
  ASSERT_FALSE(smoother.AddPose(3, Eigen::Vector3d(3, 0, 0)));
  ASSERT_FALSE(smoother.AddOdometry(2, 3, Eigen::Vector3d(1, 0, 0), info3));
  report = smoother.Update();
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.error.find("pose 2 is in a part"), std::string::npos) << report.error;
  ASSERT_FALSE(smoother.AddOdometry(1, 2, Eigen::Vector3d(1, 0, 0), info3));
  report = smoother.Update();
  EXPECT_TRUE(report.ok) << report.error;
}

// The constrained ordering: flagged indices after the other leading ones, the trailing slots
// last in natural order, and the factor still solves the system.
TEST(SparseCholeskyTest, FlaggedIndicesAreOrderedLastBeforeTheTrailingSlots) {
  const int n = 12;
  const int trailing = 2;
  // A chain (tridiagonal, diagonally dominant) in its upper triangle; the slots are isolated.
  std::vector<int> starts = {0};
  std::vector<int> rows;
  std::vector<double> values;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < n; ++c) {
    if (c > 0 && c < n - trailing) {
      rows.push_back(c - 1);
      values.push_back(-1.0);
      dense(c - 1, c) = dense(c, c - 1) = -1.0;
    }
    rows.push_back(c);
    values.push_back(4.0);
    dense(c, c) = 4.0;
    starts.push_back(static_cast<int>(rows.size()));
  }
  std::vector<char> last(n - trailing, 0);
  last[1] = last[4] = 1;
  SparseCholesky cholesky;
  ASSERT_TRUE(cholesky.Analyze(n, starts, rows, SparseCholesky::Form::kSimplicial, trailing,
                               &last));
  for (int i = 0; i < n - trailing; ++i) {
    if (last[i]) {
      EXPECT_GE(cholesky.PositionOf(i), n - trailing - 2) << i;
    } else {
      EXPECT_LT(cholesky.PositionOf(i), n - trailing - 2) << i;
    }
  }
  EXPECT_EQ(cholesky.PositionOf(n - 2), n - 2);
  EXPECT_EQ(cholesky.PositionOf(n - 1), n - 1);
  ASSERT_TRUE(cholesky.Factorize(values));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  EXPECT_LT((cholesky.Solve(b) - dense.ldlt().solve(b)).cwiseAbs().maxCoeff(), 1e-12);
  // Without trailing slots the flags still hold; a wrong number of flags is refused.
  std::vector<char> all_last(n, 0);
  all_last[0] = 1;
  ASSERT_TRUE(cholesky.Analyze(n, starts, rows, SparseCholesky::Form::kSimplicial, 0, &all_last));
  EXPECT_EQ(cholesky.PositionOf(0), n - 1);
  EXPECT_FALSE(cholesky.Analyze(n, starts, rows, SparseCholesky::Form::kSimplicial, trailing,
                                &all_last));
}

// A chain in its natural order: column j of the factor holds rows j and j + 1, its parent in
// the elimination tree is j + 1, so a rank update on row j runs along 2 (n - 1 - j) + 1 entries.
TEST(SparseCholeskyTest, ModifyWorkCountsTheEntriesAlongEachPath) {
  const int n = 8;
  std::vector<int> starts = {0};
  std::vector<int> rows;
  std::vector<double> values;
  for (int c = 0; c < n; ++c) {
    if (c > 0) {
      rows.push_back(c - 1);
      values.push_back(-1.0);
    }
    rows.push_back(c);
    values.push_back(4.0);
    starts.push_back(static_cast<int>(rows.size()));
  }
  SparseCholesky cholesky;
  EXPECT_EQ(cholesky.ModifyWork({{{0}, {1.0}}}), 0.0);  // nothing factorised yet
  // Every index "trailing": kept in its natural order.
  ASSERT_TRUE(cholesky.Analyze(n, starts, rows, SparseCholesky::Form::kSimplicial, n));
  ASSERT_TRUE(cholesky.Factorize(values));
  for (int i = 0; i < n; ++i) ASSERT_EQ(cholesky.PositionOf(i), i);
  const auto work = [](int j) { return 2.0 * (n - 1 - j) + 1.0; };
  EXPECT_EQ(cholesky.ModifyWork({{{n - 1}, {1.0}}}), 1.0);
  EXPECT_EQ(cholesky.ModifyWork({{{0}, {1.0}}}), work(0));
  // A column's path starts at its first row in the factor's ordering.
  EXPECT_EQ(cholesky.ModifyWork({{{5, 2}, {1.0, 1.0}}}), work(2));
  // Columns are counted each along its own path, shared tops included, in any order.
  EXPECT_EQ(cholesky.ModifyWork({{{4}, {1.0}}, {{2}, {1.0}}, {}}), work(4) + work(2));
  EXPECT_EQ(cholesky.ModifyWork({{{2}, {1.0}}, {{4}, {1.0}}}), work(4) + work(2));
  EXPECT_EQ(cholesky.FactorizationWork(), 4.0 * (n - 1) + 1.0);
  // The counts follow the factor as rank updates fill it: an update coupling 0 and 7 gives
  // every column a row 7.
  ASSERT_TRUE(cholesky.Modify(true, {{{0, 7}, {0.5, 0.5}}}));
  EXPECT_GT(cholesky.FactorizationWork(), 4.0 * (n - 1) + 1.0);
}

// Updates on variables eliminated far from the root (the loop closing on the first landmarks)
// cost more by rank updates than afresh: with the rule they re-order instead, and the estimate
// is the same.
TEST(SmootherTest, DearUpdatesReorderAndKeepTheEstimate) {
  const LoopProblem problem(80, 1.0, 2);
  // Linearisation points that follow the estimate closely: both runs end linearised at the same
  // point, so their estimates agree (with ISAM2's 0.1 they differ by the steps held back).
  SmootherOptions with_rule;
  with_rule.relinearize_threshold = 0.01;
  SmootherOptions without_rule = with_rule;
  without_rule.max_update_work_share = 0.0;
  Smoother a(with_rule);
  Smoother b(without_rule);
  int refactorizations_a = 0;
  int refactorizations_b = 0;
  for (int k = 0; k < 80; ++k) {
    problem.AddKeyframe(k, &a);
    problem.AddKeyframe(k, &b);
    const SolveReport report_a = a.Update();
    const SolveReport report_b = b.Update();
    ASSERT_TRUE(report_a.ok) << report_a.error;
    ASSERT_TRUE(report_b.ok) << report_b.error;
    refactorizations_a += report_a.refactorized ? 1 : 0;
    refactorizations_b += report_b.refactorized ? 1 : 0;
  }
  EXPECT_GT(refactorizations_a, refactorizations_b);
  EXPECT_LT(refactorizations_a, 40);  // most updates are still rank updates
  for (int extra = 0; extra < 10; ++extra) {
    ASSERT_TRUE(a.Update().ok);
    ASSERT_TRUE(b.Update().ok);
  }
  EXPECT_LT(MaxStateDifference(State(a, problem), State(b, problem), 80), 1e-6);
}

TEST(SmootherTest, RemovedLandmarkLeavesTheProblem) {
  const LoopProblem problem(24, 1.0, 4);
  SmootherOptions options;
  options.relinearize_threshold = 1e-6;
  options.relinearize_skip = 1;
  options.max_update_work_share = 0.0;  // the downdates are looked at, not what they cost
  Smoother smoother(options);
  for (int k = 0; k < 24; ++k) {
    problem.AddKeyframe(k, &smoother);
    ASSERT_TRUE(smoother.Update().ok);
  }
  // Converged first, so that no relinearisation asks for a refactorisation by itself.
  for (int extra = 0; extra < 5; ++extra) ASSERT_TRUE(smoother.Update().ok);
  const int factors = smoother.num_factors();
  ASSERT_FALSE(smoother.RemoveLandmark(3));
  EXPECT_TRUE(smoother.RemoveLandmark(3));  // gone
  EXPECT_FALSE(smoother.LandmarkEstimate(3));
  EXPECT_LT(smoother.num_factors(), factors);
  EXPECT_EQ(smoother.num_landmarks(), 7);
  EXPECT_TRUE(smoother.AddRangeBearing(5, 3, Eigen::Vector2d(1, 0), Eigen::Matrix2d::Identity()));
  const SolveReport after = smoother.Update();
  ASSERT_TRUE(after.ok) << after.error;
  EXPECT_FALSE(after.refactorized);  // its factors leave by rank downdates
  // Same optimum as a problem built without it.
  Smoother batch;
  problem.AddAll(&batch);
  ASSERT_FALSE(batch.RemoveLandmark(3));
  const SolveReport reference = batch.Optimize();
  for (int extra = 0; extra < 10; ++extra) ASSERT_TRUE(smoother.Update().ok);
  EXPECT_NEAR(smoother.ChiSquare(), reference.chi_square, 1e-6 * reference.chi_square);
  // The id may be used again by a new landmark.
  EXPECT_FALSE(smoother.AddLandmark(3, Eigen::Vector2d(0, 0)));
}

TEST(SmootherTest, BadInputIsRefusedWithAReason) {
  Smoother smoother;
  const Eigen::Matrix3d info3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix2d info2 = Eigen::Matrix2d::Identity();
  EXPECT_TRUE(smoother.AddPose(0, Eigen::Vector3d(NAN, 0, 0)));
  ASSERT_FALSE(smoother.AddPose(0, Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(smoother.AddPose(0, Eigen::Vector3d(1, 0, 0)));  // id in use
  ASSERT_FALSE(smoother.AddPose(1, Eigen::Vector3d(1, 0, 0)));
  ASSERT_FALSE(smoother.AddLandmark(0, Eigen::Vector2d(3, 3)));
  EXPECT_TRUE(smoother.AddLandmark(1, Eigen::Vector2d(INFINITY, 3)));
  // Unknown variables.
  auto error = smoother.AddOdometry(0, 5, Eigen::Vector3d(1, 0, 0), info3);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("unknown pose 5"), std::string::npos) << *error;
  EXPECT_TRUE(smoother.AddRangeBearing(0, 9, Eigen::Vector2d(1, 0), info2));
  EXPECT_TRUE(smoother.AddRelativePosition(7, 0, Eigen::Vector2d(1, 0), info2));
  EXPECT_TRUE(smoother.AddPosePrior(4, Eigen::Vector3d::Zero(), info3));
  EXPECT_TRUE(smoother.AddPointPrior(4, Eigen::Vector2d::Zero(), info2));
  // A pose related to itself, NaN measurements, bad information, non-positive range.
  EXPECT_TRUE(smoother.AddOdometry(0, 0, Eigen::Vector3d(1, 0, 0), info3));
  EXPECT_TRUE(smoother.AddOdometry(0, 1, Eigen::Vector3d(NAN, 0, 0), info3));
  EXPECT_TRUE(smoother.AddOdometry(0, 1, Eigen::Vector3d(1, 0, 0), -info3));
  Eigen::Matrix3d asymmetric = info3;
  asymmetric(0, 1) = 0.5;
  EXPECT_TRUE(smoother.AddOdometry(0, 1, Eigen::Vector3d(1, 0, 0), asymmetric));
  EXPECT_TRUE(smoother.AddRangeBearing(0, 0, Eigen::Vector2d(0, 0), info2));
  EXPECT_TRUE(smoother.AddRangeBearing(0, 0, Eigen::Vector2d(1, 0), info2, {NAN, 0}));
  Eigen::Matrix2d nan_information = info2;
  nan_information(1, 1) = NAN;
  EXPECT_TRUE(smoother.AddRelativePosition(0, 0, Eigen::Vector2d(1, 0), nan_information));
  EXPECT_TRUE(smoother.AddPointPrior(0, Eigen::Vector2d(NAN, 0), info2));
  EXPECT_EQ(smoother.num_factors(), 0);
  // No prior: the problem is free to move as a whole; both solvers say so.
  ASSERT_FALSE(smoother.AddOdometry(0, 1, Eigen::Vector3d(1, 0, 0), info3));
  ASSERT_FALSE(smoother.AddRangeBearing(1, 0, Eigen::Vector2d(2, 0.5), info2));
  for (const SolveReport& report : {smoother.Optimize(), smoother.Update()}) {
    EXPECT_FALSE(report.ok);
    EXPECT_NE(report.error.find("unconstrained"), std::string::npos) << report.error;
  }
  EXPECT_FALSE(smoother.PoseCovariance(0));
  // With a prior it solves, and the estimates are finite.
  ASSERT_FALSE(smoother.AddPosePrior(0, Eigen::Vector3d::Zero(), info3 * 100));
  ASSERT_TRUE(smoother.Optimize().ok);
  EXPECT_TRUE(smoother.PoseEstimate(1)->allFinite());
  EXPECT_TRUE(smoother.PoseCovariance(1)->allFinite());
  EXPECT_FALSE(smoother.PoseEstimate(42));
  EXPECT_FALSE(smoother.PoseCovariance(42));
  // An empty problem.
  Smoother empty;
  EXPECT_FALSE(empty.Optimize().ok);
  EXPECT_FALSE(empty.Update().ok);
}

TEST(SmootherTest, DegenerateGeometryIsNotAFiniteLookingGuess) {
  // A landmark seen only by bearing-less relative position is fine; one seen by range and
  // bearing from exactly where it is has an undefined bearing: the solve must fail or stay
  // finite, never return NaN.
  Smoother smoother;
  ASSERT_FALSE(smoother.AddPose(0, Eigen::Vector3d::Zero()));
  ASSERT_FALSE(smoother.AddPosePrior(0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));
  ASSERT_FALSE(smoother.AddLandmark(0, Eigen::Vector2d::Zero()));
  ASSERT_FALSE(smoother.AddRangeBearing(0, 0, Eigen::Vector2d(1, 0), Eigen::Matrix2d::Identity()));
  const SolveReport report = smoother.Optimize();
  if (report.ok) {
    EXPECT_TRUE(smoother.LandmarkEstimate(0)->allFinite());
    EXPECT_TRUE(std::isfinite(report.chi_square));
  } else {
    EXPECT_FALSE(report.error.empty());
  }
}

TEST(SmootherTest, SameInputGivesTheSameBytes) {
  const LoopProblem problem(40, 1.0, 9);
  const auto solve = [&](bool incremental) {
    Smoother smoother;
    if (incremental) {
      for (int k = 0; k < 40; ++k) {
        problem.AddKeyframe(k, &smoother);
        EXPECT_TRUE(smoother.Update().ok);
      }
    } else {
      problem.AddAll(&smoother);
      EXPECT_TRUE(smoother.Optimize().ok);
    }
    Eigen::VectorXd state = State(smoother, problem);
    std::vector<double> bytes(state.data(), state.data() + state.size());
    bytes.push_back(smoother.ChiSquare());
    const Eigen::Matrix3d covariance = *smoother.PoseCovariance(39);
    bytes.insert(bytes.end(), covariance.data(), covariance.data() + 9);
    return bytes;
  };
  for (const bool incremental : {false, true}) {
    const std::vector<double> first = solve(incremental);
    const std::vector<double> second = solve(incremental);
    ASSERT_EQ(first.size(), second.size());
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0)
        << (incremental ? "incremental" : "batch");
  }
}

// What the constructor says about options it cannot work with (CheckSmootherOptions): the
// first option out of its range, or max_lambda below initial_lambda.
std::string ConstructorError(const SmootherOptions& options) {
  try {
    Smoother smoother(options);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(SmootherOptionsTest, TheSmootherRefusesUnusableOptions) {
  EXPECT_EQ(ConstructorError(SmootherOptions()), "");
  SmootherOptions o;
  o.lambda_factor = 1.0;  // a rejected LM step would never raise lambda
  EXPECT_EQ(ConstructorError(o), "smoother options: lambda_factor = 1: must be > 1");
  o = SmootherOptions();
  o.initial_lambda = 0.0;
  EXPECT_EQ(ConstructorError(o), "smoother options: initial_lambda = 0: must be > 0");
  o = SmootherOptions();
  o.initial_lambda = 1.0;
  o.max_lambda = 0.1;
  EXPECT_EQ(ConstructorError(o), "smoother options: max_lambda must be >= initial_lambda");
  o = SmootherOptions();
  o.relative_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ConstructorError(o), "smoother options: relative_tolerance = nan: must be >= 0");
  o = SmootherOptions();
  o.max_iterations = 0;
  EXPECT_EQ(ConstructorError(o), "smoother options: max_iterations = 0: must be in [1, 1e+09]");
  o = SmootherOptions();
  o.method = static_cast<SmootherOptions::Method>(7);
  EXPECT_EQ(ConstructorError(o), "smoother options: method is not one of its choices");
}

// docs/smoother.md carries the table the schema makes.
TEST(SmootherOptionsTest, TheOptionsTableIsDocumented) {
  SmootherOptions defaults;
  OptionsMarkdownTable table;
  VisitSmootherOptions(&table, &defaults);
  std::ifstream file(std::string(SLAMMTT_SOURCE_DIR) + "/docs/smoother.md");
  ASSERT_TRUE(file.good()) << "docs/smoother.md is part of the checkout";
  std::ostringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find(table.Table()), std::string::npos)
      << "docs/smoother.md, Options: replace the table by\n"
      << table.Table();
}

}  // namespace
}  // namespace slammtt
