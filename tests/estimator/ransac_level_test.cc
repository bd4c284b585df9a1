// RANSAC's level (estimator/ransac_level.h): the sample space of ML-RANSAC (level 1's ambiguous
// pairs, still free, re-gated at the current state) and of baseline (b) (every pair), and an
// empty space drawing nothing.
#include "estimator/ransac_level.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "estimator/level1.h"
#include "estimator/scan_gating.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

// Two landmarks side by side and one measurement between them, plus a clear pair.
struct Scene : StepScene {
  Scene() {
    AddLandmark({5.0, 0.0}, 0.05);
    AddLandmark({-5.0, 0.1}, 0.05);
    AddLandmark({-5.0, -0.1}, 0.05);
    Measure({5.02, 0.0});
    Measure({-5.0, 0.02});
  }
};

TEST(RansacLevelTest, MlRansacSamplesTheAmbiguousFreePairsReGatedAtTheCurrentState) {
  Scene scene;
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  Assignment assignment(2, 3);
  const std::vector<Candidate> ambiguous =
      AssociateLevel1(gating.compatible, scan, scene.options, &predicted, &scene.state,
                      &assignment, &scene.counts);
  ASSERT_EQ(ambiguous.size(), 2u);
  const std::vector<Candidate> space =
      RansacSampleSpace(ambiguous, scan, scene.options, &predicted, scene.state, assignment);
  ASSERT_EQ(space.size(), 2u);
  const std::vector<ObjectPrediction> now = scene.Predictions();
  for (const Candidate& c : space) {
    EXPECT_EQ(c.measurement, 1);
    // The NIS at the state level 1 left, not the one of the gating.
    EXPECT_EQ(c.nis, NormalizedInnovationSquared(scene.measurements[1],
                                                 now[static_cast<size_t>(c.object)], 9.21));
  }
  // A pair whose object is taken is not in the sample space.
  assignment.Set(0, 1);
  EXPECT_TRUE(RansacSampleSpace({ambiguous[0]}, scan, scene.options, &predicted, scene.state,
                                assignment)
                  .empty());
  std::mt19937_64 rng(1);
  const RansacOutcome outcome = RunRansacLevel(ambiguous, scan, scene.options, &predicted,
                                               scene.state, Assignment(2, 3), &rng);
  EXPECT_GE(outcome.hypotheses, 1);
  ASSERT_EQ(outcome.consensus.size(), 1u);
  EXPECT_EQ(outcome.consensus[0].measurement, 1);
}

TEST(RansacLevelTest, AllPairsBaselineSamplesEveryPairWithAFiniteNis) {
  Scene scene;
  scene.options.mode = AssociationMode::kRansacAllPairs;
  ObservationPredictions predicted(scene.options.sensor);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  const std::vector<Candidate> space =
      RansacSampleSpace({}, scan, scene.options, &predicted, scene.state, Assignment(2, 3));
  ASSERT_EQ(space.size(), 6u);  // 2 measurements x 3 objects, far ones included
  EXPECT_GT(space[1].nis, 1000.0);
}

TEST(RansacLevelTest, AnEmptySampleSpaceDrawsNothing) {
  Scene scene;
  ObservationPredictions predicted(scene.options.sensor);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  std::mt19937_64 rng(5);
  const std::mt19937_64 untouched = rng;
  const RansacOutcome outcome = RunRansacLevel({}, scan, scene.options, &predicted, scene.state,
                                               Assignment(2, 3), &rng);
  EXPECT_EQ(outcome.hypotheses, 0);
  EXPECT_TRUE(outcome.consensus.empty());
  EXPECT_TRUE(rng == untouched);
  EXPECT_EQ(predicted.computations(), 0) << "nothing to judge, nothing predicted";
}

}  // namespace
}  // namespace slammtt
