// The leg features (perception/leg_features.h) on ray-cast arcs and flat pieces with known
// geometry, and the leg classifier's evaluation and model checks (perception/leg_classifier.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "perception/leg_classifier.h"
#include "perception/leg_features.h"
#include "perception/segmenter_options.h"

namespace slammtt {
namespace {

struct Points {
  std::vector<double> bearing, range, x, y;
  ClusterView View() const {
    ClusterView v;
    v.bearing_rad = bearing.data();
    v.range_m = range.data();
    v.x_m = x.data();
    v.y_m = y.data();
    v.count = bearing.size();
    return v;
  }
};

// Beams every spacing_rad that hit a circle of `radius` at distance d on the x axis, rotated by
// `rotation` about the sensor.
Points CircleArc(double d, double radius, double spacing_rad, double rotation = 0.0) {
  Points p;
  const double half = std::asin(radius / d);
  for (double b = -half; b <= half; b += spacing_rad) {
    // Ray-circle: smallest t with |t u - c| = radius.
    const double proj = d * std::cos(b);
    const double disc = proj * proj - (d * d - radius * radius);
    if (disc < 0.0) continue;
    const double t = proj - std::sqrt(disc);
    p.bearing.push_back(b + rotation);
    p.range.push_back(t);
    p.x.push_back(t * std::cos(b + rotation));
    p.y.push_back(t * std::sin(b + rotation));
  }
  return p;
}

// A flat board at x = d, |y| <= half_width.
Points FlatPiece(double d, double half_width, double spacing_rad) {
  Points p;
  const double half = std::atan(half_width / d);
  for (double b = -half; b <= half; b += spacing_rad) {
    const double t = d / std::cos(b);
    p.bearing.push_back(b);
    p.range.push_back(t);
    p.x.push_back(t * std::cos(b));
    p.y.push_back(t * std::sin(b));
  }
  return p;
}

constexpr double kDeg = M_PI / 180.0;

TEST(LegFeaturesTest, ArcOfALegHasItsSizeCurvatureAndPoints) {
  const Points arc = CircleArc(2.0, 0.06, 0.35 * kDeg);
  ClusterSurroundings around;
  around.range_before_m = 4.0;  // a wall behind
  around.range_after_m = 4.0;
  const LegFeatureVector f = ComputeLegFeatures(arc.View(), around);
  EXPECT_EQ(f[kPoints], static_cast<float>(arc.bearing.size()));
  EXPECT_NEAR(f[kRange], 1.95, 0.02);
  EXPECT_NEAR(f[kBeamGap], 1.95 * 0.35 * kDeg, 1e-3);
  EXPECT_NEAR(f[kCircleRadius], 0.06, 1e-4);
  EXPECT_LT(f[kCircleRms], 1e-5f);
  EXPECT_GT(f[kLineRms], 0.005f);
  EXPECT_NEAR(f[kMeanCurvature], 1.0 / 0.06, 0.5);
  EXPECT_GT(f[kMeanTurn], 0.0f);
  EXPECT_GT(f[kConvexity], 0.4f);
  EXPECT_FLOAT_EQ(f[kJumpBefore], static_cast<float>(kLegJumpCapM));  // clamped
  EXPECT_FLOAT_EQ(f[kJumpAfter], static_cast<float>(kLegJumpCapM));
  EXPECT_NEAR(f[kWidth], 0.11, 0.01);
  // More than the width, less than the half circle the sensor can see.
  EXPECT_GT(f[kBoundaryLength], f[kWidth]);
  EXPECT_LT(f[kBoundaryLength], M_PI * 0.06);
}

TEST(LegFeaturesTest, FlatPieceIsStraightWithoutCurvature) {
  const Points board = FlatPiece(3.0, 0.1, 0.35 * kDeg);
  const LegFeatureVector f = ComputeLegFeatures(board.View(), ClusterSurroundings{});
  EXPECT_LT(f[kLineRms], 1e-5f);
  EXPECT_NEAR(f[kConvexity], 0.0, 1e-3);
  EXPECT_NEAR(f[kMeanCurvature], 0.0, 1e-3);
  EXPECT_GT(f[kWidth], 0.17f);  // the edge beams fall inside the board's ends
  EXPECT_LE(f[kWidth], 0.2f);
  // Collinear points have no circle: no fit, or one that fits badly.
  EXPECT_TRUE(f[kCircleRadius] == static_cast<float>(kLegRadiusCapM) || f[kCircleRms] > 0.02f);
  // Neighbours without a usable return: far behind.
  EXPECT_FLOAT_EQ(f[kJumpBefore], static_cast<float>(kLegJumpCapM));
}

TEST(LegFeaturesTest, JumpsAreSignedRangeDifferences) {
  const Points arc = CircleArc(2.0, 0.06, 0.35 * kDeg);
  ClusterSurroundings around;
  around.range_before_m = arc.range.front() - 0.3;  // a nearer object hides the first edge
  around.range_after_m = arc.range.back() + 0.25;
  const LegFeatureVector f = ComputeLegFeatures(arc.View(), around);
  EXPECT_NEAR(f[kJumpBefore], -0.3, 1e-5);
  EXPECT_NEAR(f[kJumpAfter], 0.25, 1e-5);
}

TEST(LegFeaturesTest, RotatingTheFrameAboutTheSensorChangesNothing) {
  const Points a = CircleArc(3.0, 0.07, 0.9 * kDeg);
  const Points b = CircleArc(3.0, 0.07, 0.9 * kDeg, 1.3);
  const LegFeatureVector fa = ComputeLegFeatures(a.View(), ClusterSurroundings{});
  const LegFeatureVector fb = ComputeLegFeatures(b.View(), ClusterSurroundings{});
  for (int k = 0; k < kNumLegFeatures; ++k) {
    EXPECT_NEAR(fa[k], fb[k], 1e-4 * (1.0 + std::abs(static_cast<double>(fa[k]))))
        << kLegFeatureNames[k];
  }
}

TEST(LegFeaturesTest, TinyClustersGiveFiniteFeatures) {
  for (size_t n : {1u, 2u}) {
    Points p = CircleArc(1.0, 0.06, 0.9 * kDeg);
    ASSERT_GE(p.bearing.size(), 2u);
    p.bearing.resize(n);
    p.range.resize(n);
    p.x.resize(n);
    p.y.resize(n);
    ClusterSurroundings around;
    around.scan_spacing_rad = 0.9 * kDeg;
    const LegFeatureVector f = ComputeLegFeatures(p.View(), around);
    for (int k = 0; k < kNumLegFeatures; ++k) EXPECT_TRUE(std::isfinite(f[k])) << k;
    EXPECT_EQ(f[kPoints], static_cast<float>(n));
    EXPECT_EQ(f[kMeanCurvature], 0.0f);
    EXPECT_GT(f[kBeamGap], 0.0f);
  }
}

// Two stumps: x[kWidth] <= 0.2 -> +1 else -1; x[kPoints] <= 5 -> -0.5 else +0.5.
TEST(LegClassifierTest, MarginIsTheBiasPlusOneLeafPerTree) {
  const LegTreeNode nodes[] = {
      {kWidth, 0.2f, 1, 2, 0.0f}, {-1, 0.0f, -1, -1, 1.0f}, {-1, 0.0f, -1, -1, -1.0f},
      {kPoints, 5.0f, 4, 5, 0.0f}, {-1, 0.0f, -1, -1, -0.5f}, {-1, 0.0f, -1, -1, 0.5f}};
  const int32_t roots[] = {0, 3};
  const LegModel model{nodes, 6, roots, 2, 0.25, 0.5};
  EXPECT_STREQ(CheckLegModel(model), "");
  LegFeatureVector x{};
  x[kWidth] = 0.2f;  // <= goes left
  x[kPoints] = 6.0f;
  EXPECT_DOUBLE_EQ(LegModelMargin(model, x), 0.25 + 1.0 + 0.5);
  x[kWidth] = 0.3f;
  x[kPoints] = 5.0f;
  EXPECT_DOUBLE_EQ(LegModelMargin(model, x), 0.25 - 1.0 - 0.5);
  EXPECT_NEAR(LegProbability(model, x), 1.0 / (1.0 + std::exp(1.25)), 1e-12);
}

TEST(LegClassifierTest, MalformedModelsAreFound) {
  LegTreeNode nodes[] = {{kWidth, 0.2f, 1, 7, 0.0f}, {-1, 0.0f, -1, -1, 1.0f}};
  const int32_t roots[] = {0};
  EXPECT_STRNE(CheckLegModel(LegModel{nodes, 2, roots, 1, 0.0, 0.5}), "");  // child 7
  nodes[0].right = 0;  // a loop
  EXPECT_STRNE(CheckLegModel(LegModel{nodes, 2, roots, 1, 0.0, 0.5}), "");
  nodes[0].right = 1;
  nodes[0].feature = kNumLegFeatures;
  EXPECT_STRNE(CheckLegModel(LegModel{nodes, 2, roots, 1, 0.0, 0.5}), "");
  nodes[0].feature = kWidth;
  nodes[1].value = NAN;
  EXPECT_STRNE(CheckLegModel(LegModel{nodes, 2, roots, 1, 0.0, 0.5}), "");
  const int32_t bad_root[] = {5};
  nodes[1].value = 1.0f;
  EXPECT_STRNE(CheckLegModel(LegModel{nodes, 2, bad_root, 1, 0.0, 0.5}), "");
  EXPECT_STREQ(CheckLegModel(LegModel{nodes, 2, roots, 1, 0.0, 0.5}), "");
}

TEST(LegClassifierTest, TheTrainedModelIsWellFormedAndSetsTheDefaultThreshold) {
  const LegModel& model = TrainedLegModel();
  EXPECT_STREQ(CheckLegModel(model), "");
  EXPECT_GT(model.num_trees, 0u);
  EXPECT_EQ(SegmenterOptions{}.leg_threshold, model.suggested_threshold);
  EXPECT_EQ(SegmenterOptions{}.leg_classifier, LegClassifier::kTrained);
}

}  // namespace
}  // namespace slammtt
