// Which centre rule puts a round object's feature nearest its true centre. Arcs of circles with
// known centres (people and posts: radius 0.05-0.35 m, at 0.5-8 m) are ray-cast at RPLIDAR A2
// spacing (0.9 deg) and at a finer one, with range noise, and every rule's centre error is
// collected. The paper's middle point must show its bias of about one radius, and the default
// rule must beat it and the other rule.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "perception/centre_estimation.h"
#include "perception/segmenter.h"
#include "tests/perception/synthetic_scan.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

using testing_support::CastScan;
using testing_support::Circle;
using testing_support::EvenAngles;
using testing_support::Percentile;

constexpr double kDeg = M_PI / 180.0;

struct RuleErrors {
  std::vector<double> middle_point;
  std::vector<double> radius_corrected;
  std::vector<double> circle_fit;
};

double CentreError(const Feature& f, const Circle& c) {
  return std::hypot(f.range_m * std::cos(f.bearing_rad) - c.x_m,
                    f.range_m * std::sin(f.bearing_rad) - c.y_m);
}

// One object per scan, so that every rule sees exactly the same cluster.
RuleErrors CollectErrors(double spacing_rad, double range_sigma_m, uint64_t seed, int trials) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius_m(0.05, 0.35);
  std::uniform_real_distribution<double> distance_m(0.5, 8.0);
  std::uniform_real_distribution<double> bearing_rad(-M_PI, M_PI);
  const int beams = static_cast<int>(std::lround(2.0 * M_PI / spacing_rad));
  const std::vector<double> angles = EvenAngles(-M_PI, 2.0 * M_PI, beams, true);
  SegmenterOptions options;
  options.sigma_r_m = std::max(0.03, range_sigma_m);
  RuleErrors errors;
  for (int trial = 0; trial < trials; ++trial) {
    const double d = distance_m(rng);
    const double b = bearing_rad(rng);
    const Circle circle{d * std::cos(b), d * std::sin(b), radius_m(rng)};
    if (circle.radius_m >= 0.9 * d) continue;
    const testing_support::TestScan scan = CastScan({circle}, angles, 12.0, range_sigma_m, &rng);
    for (CentreRule rule :
         {CentreRule::kMiddlePoint, CentreRule::kRadiusCorrected, CentreRule::kCircleFit}) {
      options.centre_rule = rule;
      const std::vector<Feature> features = SegmentScan(scan.View(), options);
      if (features.size() != 1) continue;  // fewer than min_points beams: not a feature
      const double error = CentreError(features[0], circle);
      if (rule == CentreRule::kMiddlePoint) errors.middle_point.push_back(error);
      if (rule == CentreRule::kRadiusCorrected) errors.radius_corrected.push_back(error);
      if (rule == CentreRule::kCircleFit) errors.circle_fit.push_back(error);
    }
  }
  return errors;
}

void Print(const char* label, const RuleErrors& e) {
  std::printf("%s: n=%zu  median / p95 centre error [m]: middle_point %.4f / %.4f, "
              "radius_corrected %.4f / %.4f, circle_fit %.4f / %.4f\n",
              label, e.middle_point.size(), Percentile(e.middle_point, 0.5),
              Percentile(e.middle_point, 0.95), Percentile(e.radius_corrected, 0.5),
              Percentile(e.radius_corrected, 0.95), Percentile(e.circle_fit, 0.5),
              Percentile(e.circle_fit, 0.95));
}

void ExpectDefaultRuleIsBest(const RuleErrors& e) {
  ASSERT_GT(e.middle_point.size(), 300u);
  ASSERT_EQ(e.middle_point.size(), e.radius_corrected.size());
  ASSERT_EQ(e.middle_point.size(), e.circle_fit.size());
  const double middle = Percentile(e.middle_point, 0.5);
  const double corrected = Percentile(e.radius_corrected, 0.5);
  const double fit = Percentile(e.circle_fit, 0.5);
  // The paper's rule is biased by about one radius (radii 0.05-0.35 m, median 0.2 m).
  EXPECT_GT(middle, 0.1);
  const SegmenterOptions defaults;
  const double best_other = std::min(middle, defaults.centre_rule == CentreRule::kCircleFit
                                                 ? corrected
                                                 : fit);
  const double chosen = defaults.centre_rule == CentreRule::kCircleFit ? fit : corrected;
  EXPECT_NE(defaults.centre_rule, CentreRule::kMiddlePoint);
  EXPECT_LT(chosen, best_other) << "the default rule " << CentreRuleName(defaults.centre_rule)
                                << " is not the most accurate one";
  EXPECT_LT(chosen, 0.5 * middle);
  EXPECT_LT(Percentile(defaults.centre_rule == CentreRule::kCircleFit ? e.circle_fit
                                                                      : e.radius_corrected,
                       0.95),
            Percentile(e.middle_point, 0.95));
}

TEST(CentreRuleTest, DefaultRuleBeatsMiddlePointAtRplidarSpacing) {
  const RuleErrors errors = CollectErrors(0.9 * kDeg, 0.01, 11, 1500);
  Print("RPLIDAR A2 spacing 0.9 deg, range noise 0.01 m", errors);
  ExpectDefaultRuleIsBest(errors);
}

TEST(CentreRuleTest, DefaultRuleBeatsMiddlePointWithPaperNoise) {
  const RuleErrors errors = CollectErrors(0.9 * kDeg, 0.03, 12, 1500);
  Print("RPLIDAR A2 spacing 0.9 deg, range noise 0.03 m", errors);
  ExpectDefaultRuleIsBest(errors);
}

TEST(CentreRuleTest, DefaultRuleBeatsMiddlePointAtFineSpacing) {
  const RuleErrors errors = CollectErrors(0.25 * kDeg, 0.01, 13, 1000);
  Print("spacing 0.25 deg, range noise 0.01 m", errors);
  ExpectDefaultRuleIsBest(errors);
}

// Noise-free arcs: the two corrected rules find the centre closely, the middle point is one
// radius short along the beam.
TEST(CentreRuleTest, NoiseFreeArcGeometry) {
  const Circle post{3.0, 0.5, 0.2};
  const std::vector<double> angles = EvenAngles(-M_PI, 2.0 * M_PI, 1440, true);
  const testing_support::TestScan scan = CastScan({post}, angles);
  SegmenterOptions options;
  options.centre_rule = CentreRule::kMiddlePoint;
  const std::vector<Feature> middle = SegmentScan(scan.View(), options);
  ASSERT_EQ(middle.size(), 1u);
  const double true_range = std::hypot(post.x_m, post.y_m);
  EXPECT_NEAR(middle[0].range_m, true_range - post.radius_m, 0.005);
  EXPECT_NEAR(middle[0].bearing_rad, std::atan2(post.y_m, post.x_m), 0.25 * kDeg);
  for (CentreRule rule : {CentreRule::kRadiusCorrected, CentreRule::kCircleFit}) {
    options.centre_rule = rule;
    const std::vector<Feature> f = SegmentScan(scan.View(), options);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_LT(CentreError(f[0], post), 0.01) << CentreRuleName(rule);
    EXPECT_NEAR(f[0].radius_m, post.radius_m, 0.01) << CentreRuleName(rule);
  }
}

// A flat face (a board, a box seen face-on) is not a circle: both corrected rules still put its
// centre behind the face, by at most half its width, and on its middle bearing.
TEST(CentreRuleTest, FlatFaceCentreIsBehindTheFace) {
  std::vector<double> bearing, range, x, y;
  for (int i = 0; i < 9; ++i) {  // a flat board 2 m ahead, 0.4 m wide
    const double py = -0.2 + 0.05 * i;
    x.push_back(2.0);
    y.push_back(py);
    range.push_back(std::hypot(2.0, py));
    bearing.push_back(std::atan2(py, 2.0));
  }
  ClusterView cluster{bearing.data(), range.data(), x.data(), y.data(), bearing.size()};
  const CentreEstimate corrected = RadiusCorrectedCentre(cluster, 1.0);
  const CentreEstimate fit = CircleFitCentre(cluster, 1.0, 0.03);
  for (const CentreEstimate& e : {corrected, fit}) {
    EXPECT_GT(e.range_m, 2.0);
    EXPECT_LT(e.range_m, 2.0 + 0.25);
    EXPECT_NEAR(e.bearing_rad, 0.0, 1e-9);
  }
  EXPECT_FALSE(fit.fell_back);
}

// Without usable tangents (both edges occluded) the fit needs kMinCircleFitPoints points.
TEST(CentreRuleTest, CircleFitFallsBackWithoutTangentsAndFewPoints) {
  const Circle post{2.0, 0.0, 0.2};
  std::vector<double> bearing, range, x, y;
  for (int i = -2; i <= 2; ++i) {
    const double b = i * 1.0 * kDeg;
    const double r = testing_support::RayCircle(b, post);
    bearing.push_back(b);
    range.push_back(r);
    x.push_back(r * std::cos(b));
    y.push_back(r * std::sin(b));
  }
  ClusterView cluster{bearing.data(), range.data(), x.data(), y.data(), bearing.size()};
  cluster.first_edge_occluded = true;
  cluster.last_edge_occluded = true;
  const CentreEstimate five = CircleFitCentre(cluster, 1.0, 0.03);
  EXPECT_FALSE(five.fell_back);
  // Noise-free points on a 4-degree arc: range and radius are nearly interchangeable (the near
  // side is what is seen), so three Gauss-Newton steps get within millimetres, not to zero. The
  // start, which takes the occluded edges for tangents, is 0.1 m short.
  EXPECT_NEAR(five.range_m, 2.0, 0.005);
  EXPECT_NEAR(five.radius_m, 0.2, 0.005);
  const CentreEstimate start = RadiusCorrectedCentre(cluster, 1.0);
  EXPECT_GT(std::abs(start.range_m - 2.0), 0.05);
  cluster.count = kMinCircleFitPoints - 1;
  EXPECT_TRUE(CircleFitCentre(cluster, 1.0, 0.03).fell_back);
  cluster.last_edge_occluded = false;  // one tangent + 4 points: enough
  EXPECT_FALSE(CircleFitCentre(cluster, 1.0, 0.03).fell_back);
}

// A partly hidden post: the occluded edge's tangent is not used, so the fit keeps the radius.
TEST(CentreRuleTest, CircleFitIgnoresTheOccludedEdge) {
  const Circle post{4.0, 0.0, 0.25};
  std::vector<double> bearing, range, x, y;
  // The post subtends +-3.58 deg. Beams from -2.7 to +0.9 deg hit it; beyond +0.9 deg another
  // object is in front.
  for (int i = -3; i <= 1; ++i) {
    const double b = i * 0.9 * kDeg;
    const double r = testing_support::RayCircle(b, post);
    ASSERT_GT(r, 0.0);
    bearing.push_back(b);
    range.push_back(r);
    x.push_back(r * std::cos(b));
    y.push_back(r * std::sin(b));
  }
  ClusterView cluster{bearing.data(), range.data(), x.data(), y.data(), bearing.size()};
  auto error = [&](const CentreEstimate& e) {
    return std::hypot(e.range_m * std::cos(e.bearing_rad) - post.x_m,
                      e.range_m * std::sin(e.bearing_rad) - post.y_m);
  };
  const CentreEstimate naive = CircleFitCentre(cluster, 1.0, 0.01);
  cluster.last_edge_occluded = true;
  const CentreEstimate aware = CircleFitCentre(cluster, 1.0, 0.01);
  ASSERT_FALSE(aware.fell_back);
  // The remaining tangent is known to half a beam spacing (0.45 deg = 3 cm at 4 m).
  EXPECT_LT(error(aware), 0.05);
  EXPECT_NEAR(aware.radius_m, post.radius_m, 0.05);
  // Taking the occlusion edge for the outline shrinks the object and shifts its centre.
  EXPECT_GT(error(naive), 2.0 * error(aware));
  std::printf("partly hidden post: centre error %.3f m with the occluded edge ignored, %.3f m "
              "when it is taken for a tangent\n", error(aware), error(naive));
}

TEST(CentreRuleTest, RadiusIsClampedToTheMaximum) {
  // A large drum (radius 0.8 m) 3 m away with a maximum radius of 0.3 m.
  const Circle drum{3.0, 0.0, 0.8};
  const testing_support::TestScan scan =
      CastScan({drum}, EvenAngles(-M_PI, 2.0 * M_PI, 400, true));
  SegmenterOptions options;
  options.centre_rule = CentreRule::kRadiusCorrected;
  options.max_object_radius_m = 0.3;
  options.max_width_m = 2.0;  // the drum is 1.5 m wide as seen
  const std::vector<Feature> f = SegmentScan(scan.View(), options);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_DOUBLE_EQ(f[0].radius_m, 0.3);
  // The near side is at 2.2 m. A 0.3 m circle fitted to the middle of the much flatter face
  // touches it at 2.2 m in the middle and a little further out at its sides: 2.2 + (0.2..0.3).
  EXPECT_GT(f[0].range_m, 2.2 + 0.2);
  EXPECT_LT(f[0].range_m, 2.2 + 0.3);
}

TEST(CentreRuleTest, RuleNamesRoundTrip) {
  for (CentreRule rule :
       {CentreRule::kMiddlePoint, CentreRule::kRadiusCorrected, CentreRule::kCircleFit}) {
    CentreRule parsed = CentreRule::kMiddlePoint;
    ASSERT_TRUE(ParseCentreRule(CentreRuleName(rule), &parsed));
    EXPECT_EQ(parsed, rule);
  }
  CentreRule parsed = CentreRule::kCircleFit;
  EXPECT_FALSE(ParseCentreRule("middle", &parsed));
  EXPECT_EQ(parsed, CentreRule::kCircleFit);
}

// The circle fit's residuals (CirclePointResidual, CircleTangentBearing): their Jacobians with
// respect to (D, theta, R) against central differences, at circles in front of and beside the
// sensor, for points on every side of the centre and both tangents.
TEST(CircleFitResidualTest, JacobiansMatchNumericalDerivatives) {
  using testing::NumericalJacobian;
  const Eigen::Vector3d circles[] = {{3.0, 0.2, 0.25}, {1.2, -1.4, 0.1}, {8.0, 2.9, 0.6}};
  for (const Eigen::Vector3d& c : circles) {
    const FitCircle circle(c(0), c(1), c(2));
    for (double angle = 0.0; angle < 2.0 * M_PI; angle += 0.7) {
      const double x = circle.centre_x_m + 0.8 * c(2) * std::cos(angle);
      const double y = circle.centre_y_m + 0.8 * c(2) * std::sin(angle);
      double residual = 0.0;
      Eigen::Vector3d jacobian;
      ASSERT_TRUE(CirclePointResidual(circle, x, y, &residual, &jacobian));
      EXPECT_NEAR(residual, -0.2 * c(2), 1e-12);
      const Eigen::MatrixXd numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
            double e = 0.0;
            Eigen::Vector3d unused;
            CirclePointResidual(FitCircle(v(0), v(1), v(2)), x, y, &e, &unused);
            return Eigen::Matrix<double, 1, 1>(e);
          },
          c);
      EXPECT_LT((jacobian.transpose() - numerical).cwiseAbs().maxCoeff(), 1e-7)
          << "circle " << c.transpose() << ", point at angle " << angle;
    }
    for (int side : {-1, 1}) {
      Eigen::Vector3d jacobian;
      const double tangent = CircleTangentBearing(circle, side, &jacobian);
      EXPECT_NEAR(tangent, c(1) + side * std::asin(c(2) / c(0)), 1e-12);
      const Eigen::MatrixXd numerical = NumericalJacobian(
          [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
            Eigen::Vector3d unused;
            return Eigen::Matrix<double, 1, 1>(
                CircleTangentBearing(FitCircle(v(0), v(1), v(2)), side, &unused));
          },
          c);
      EXPECT_LT((jacobian.transpose() - numerical).cwiseAbs().maxCoeff(), 1e-7)
          << "circle " << c.transpose() << ", side " << side;
    }
  }
  // A point at the centre has no gradient.
  const FitCircle circle(3.0, 0.0, 0.2);
  double residual = 0.0;
  Eigen::Vector3d jacobian;
  EXPECT_FALSE(CirclePointResidual(circle, circle.centre_x_m, circle.centre_y_m, &residual,
                                   &jacobian));
}

}  // namespace
}  // namespace slammtt
