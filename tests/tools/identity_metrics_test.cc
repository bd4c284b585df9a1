// IDF1 and HOTA on hand-computed cases (tools/metrics/identity_metrics.h; every figure worked out
// in the comments).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tools/metrics/identity_metrics.h"

namespace slammtt {
namespace {

IdentifiedPoint At(int64_t id, double x, double y = 0.0) { return {id, Eigen::Vector2d(x, y)}; }

TEST(IdentityMetricsTest, PerfectTrackingScoresOne) {
  IdentityMetricsAccumulator metrics(1.0);
  for (int k = 0; k < 10; ++k) metrics.AddFrame({At(7, k)}, {At(70, k)});
  const IdentityScores s = metrics.Scores();
  EXPECT_EQ(s.id_true_positives, 10);
  EXPECT_DOUBLE_EQ(*s.idf1, 1.0);
  EXPECT_DOUBLE_EQ(*s.hota, 1.0);
  EXPECT_DOUBLE_EQ(*s.det_a, 1.0);
  EXPECT_DOUBLE_EQ(*s.ass_a, 1.0);
  EXPECT_DOUBLE_EQ(*s.loc_a, 1.0);
}

TEST(IdentityMetricsTest, AnIdentitySwitchHalvesIdf1AndAssociation) {
  // Truth 7 is tracked by 70 in frames 0-4 and by 71 in frames 5-9, exactly. IDF1: 7 <-> 70
  // (5 frames), IDTP 5 of 10 + 10 detections: 2 * 5 / 20 = 0.5. HOTA: every frame a true
  // positive at every alpha (DetA 1); each TP's association 5 / (10 + 5 - 5) = 0.5 (AssA 0.5),
  // so HOTA = sqrt(0.5).
  IdentityMetricsAccumulator metrics(1.0);
  for (int k = 0; k < 10; ++k) metrics.AddFrame({At(7, k)}, {At(k < 5 ? 70 : 71, k)});
  const IdentityScores s = metrics.Scores();
  EXPECT_EQ(s.id_true_positives, 5);
  EXPECT_EQ(s.id_false_negatives, 5);
  EXPECT_EQ(s.id_false_positives, 5);
  EXPECT_DOUBLE_EQ(*s.idf1, 0.5);
  EXPECT_DOUBLE_EQ(*s.det_a, 1.0);
  EXPECT_DOUBLE_EQ(*s.ass_a, 0.5);
  EXPECT_DOUBLE_EQ(*s.hota, std::sqrt(0.5));
}

TEST(IdentityMetricsTest, LocalisationCountsOnlyTheAlphasTheSimilarityReaches) {
  // Distance 0.42 with threshold 1: S = 0.58, a true positive for alpha 0.05 ... 0.55 (11 of the
  // 19 alphas), where DetA = AssA = 1; none for the other 8. HOTA = DetA = AssA = 11/19;
  // LocA = (11 * 0.58 + 8 * 1) / 19 (an alpha without a true positive has LocA 1, as TrackEval).
  IdentityMetricsAccumulator metrics(1.0);
  for (int k = 0; k < 4; ++k) metrics.AddFrame({At(1, k)}, {At(2, k, 0.42)});
  const IdentityScores s = metrics.Scores();
  EXPECT_DOUBLE_EQ(*s.idf1, 1.0);
  EXPECT_NEAR(*s.hota, 11.0 / 19.0, 1e-12);
  EXPECT_NEAR(*s.det_a, 11.0 / 19.0, 1e-12);
  EXPECT_NEAR(*s.ass_a, 11.0 / 19.0, 1e-12);
  EXPECT_NEAR(*s.loc_a, (11.0 * 0.58 + 8.0) / 19.0, 1e-12);
}

TEST(IdentityMetricsTest, TheGlobalMatchPrefersTheLongerCommonStretch) {
  // Truth 1 is followed by 10 for 2 frames, then by 11 for 6; truth 2 (present all 8 frames)
  // by 10 in those 6 frames (10 jumps to it). Best trajectory matching: 1 <-> 11 (6 frames) and
  // 2 <-> 10 (6), IDTP 12, not 1 <-> 10 (2). Detections: 16 true, 2 + 6 + 6 = 14 hypothesis;
  // IDF1 = 2 * 12 / 30.
  IdentityMetricsAccumulator metrics(0.5);
  for (int k = 0; k < 8; ++k) {
    std::vector<IdentifiedPoint> hypotheses;
    if (k < 2) {
      hypotheses = {At(10, k)};
    } else {
      hypotheses = {At(11, k), At(10, k, 5.0)};
    }
    metrics.AddFrame({At(1, k), At(2, k, 5.0)}, hypotheses);
  }
  const IdentityScores s = metrics.Scores();
  EXPECT_EQ(s.num_truth_detections, 16);
  EXPECT_EQ(s.num_hypothesis_detections, 14);
  EXPECT_EQ(s.id_true_positives, 12);
  EXPECT_DOUBLE_EQ(*s.idf1, 24.0 / 30.0);
}

TEST(IdentityMetricsTest, NothingMatchedScoresZeroAndNothingAtAllScoresNothing) {
  IdentityMetricsAccumulator far(1.0);
  for (int k = 0; k < 4; ++k) far.AddFrame({At(1, 0)}, {At(2, 5)});
  const IdentityScores s = far.Scores();
  EXPECT_DOUBLE_EQ(*s.idf1, 0.0);
  EXPECT_DOUBLE_EQ(*s.hota, 0.0);
  EXPECT_DOUBLE_EQ(*s.det_a, 0.0);
  IdentityMetricsAccumulator empty(1.0);
  empty.AddFrame({}, {});
  EXPECT_FALSE(empty.Scores().idf1.has_value());
  EXPECT_FALSE(empty.Scores().hota.has_value());
  IdentityMetricsAccumulator only_truth(1.0);
  only_truth.AddFrame({At(1, 0)}, {});
  EXPECT_DOUBLE_EQ(*only_truth.Scores().idf1, 0.0);
  EXPECT_FALSE(only_truth.Scores().id_precision.has_value());
}

TEST(IdentityMetricsTest, BadInputIsRejected) {
  EXPECT_THROW(IdentityMetricsAccumulator(0.0), std::invalid_argument);
  IdentityMetricsAccumulator metrics(1.0);
  EXPECT_THROW(metrics.AddFrame({At(1, 0), At(1, 1)}, {}), std::invalid_argument);
  EXPECT_THROW(metrics.AddFrame({}, {At(1, NAN)}), std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
