// Choices between pairs that share a measurement go by PairCost, NIS + ln det S (gating.h), not
// by the NIS alone: RANSAC's tie-break between hypotheses of equal consensus and its one-to-one
// consensus, and level 3's greedy choice (estimator.cc) use it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "estimator/gating.h"
#include "estimator/ml_ransac.h"
#include "estimator/slam_state.h"

namespace slammtt {
namespace {

// A robot at the origin known to 1 mm and 0.1 mrad; a landmark 3 m ahead known to 1 cm
// (object 0) and an object known to 1 m a little farther (object 1, e.g. a track coasting
// unseen). One measurement 5 cm behind the landmark (range sigma 3 cm, bearing 0.01 rad): its
// NIS to the landmark is about 2.3, to the wide object about 0.02.
struct Scene {
  SlamState state{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
  std::vector<PointMeasurement> measurements;
  Scene() {
    const Eigen::Matrix<double, 2, 3> no_robot = Eigen::Matrix<double, 2, 3>::Zero();
    ObjectRecord landmark;
    landmark.id = 1;
    landmark.object_class = ObjectClass::kStatic;
    state.AddObject(Eigen::Vector2d(3.0, 0.0), no_robot, 1e-4 * Eigen::Matrix2d::Identity(),
                    landmark);
    ObjectRecord wide;
    wide.id = 2;
    state.AddObject(Eigen::Vector2d(3.2, 0.0), no_robot, Eigen::Matrix2d::Identity(), wide);
    PointMeasurement z;
    z.range_bearing = Eigen::Vector2d(3.05, 0.0);
    z.covariance = Eigen::Vector2d(0.03 * 0.03, 0.01 * 0.01).asDiagonal();
    measurements.push_back(z);
  }
};

TEST(PairCostTest, IsTheNisPlusTheLogDeterminantOfS) {
  Scene scene;
  const std::vector<ObjectPrediction> p = PredictObservations(scene.state, SensorMount());
  const PointMeasurement& z = scene.measurements[0];
  for (int j = 0; j < 2; ++j) {
    const double nis = NormalizedInnovationSquared(z, p[static_cast<size_t>(j)], 1e9);
    const Eigen::Matrix2d s = p[static_cast<size_t>(j)].hph + z.covariance;
    EXPECT_NEAR(PairCost(z, p[static_cast<size_t>(j)], nis), nis + std::log(s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0)),
                1e-9);
  }
  const double nis_landmark = NormalizedInnovationSquared(z, p[0], 1e9);
  const double nis_wide = NormalizedInnovationSquared(z, p[1], 1e9);
  EXPECT_GT(nis_landmark, 10.0 * nis_wide) << "the NIS alone prefers the wide object";
  EXPECT_LT(PairCost(z, p[0], nis_landmark), PairCost(z, p[1], nis_wide) - 5.0)
      << "the likelihood prefers the landmark";
  ObjectPrediction invalid = p[0];
  invalid.valid = false;
  EXPECT_TRUE(std::isinf(PairCost(z, invalid, nis_landmark)));
}

TEST(PairCostTest, RansacGivesTheMeasurementToTheWellKnownLandmark) {
  Scene scene;
  const std::vector<ObjectPrediction> p = PredictObservations(scene.state, SensorMount());
  const PointMeasurement& z = scene.measurements[0];
  // Both pairs are in the sample space; each hypothesis has a consensus of one pair, so the
  // cost decides. The pair order is the one by which the wide object would win a tie.
  const std::vector<Candidate> pairs = {{0, 1, NormalizedInnovationSquared(z, p[1], 1e9)},
                                        {0, 0, NormalizedInnovationSquared(z, p[0], 1e9)}};
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    std::mt19937_64 rng(seed);
    const RansacOutcome outcome = RunOnePointRansac(scene.state, scene.measurements, p, pairs,
                                                    pairs, SensorMount(), RansacOptions(), &rng);
    ASSERT_EQ(outcome.consensus.size(), 1u);
    EXPECT_EQ(outcome.consensus[0].object, 0) << "seed " << seed;
    EXPECT_EQ(outcome.best_pair, 1);
  }
}

}  // namespace
}  // namespace slammtt
