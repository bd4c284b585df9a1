// The features of a scan as the estimator takes them (estimator/feature_validation.h) and the
// gating step (estimator/scan_gating.h).
#include "estimator/feature_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "estimator/scan_gating.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

FeatureReading Feature(double range_m, double bearing_rad, double range_var = 0.0,
                       double bearing_var = 0.0, double width_m = 0.0) {
  FeatureReading f;
  f.range_m = range_m;
  f.bearing_rad = bearing_rad;
  f.range_var_m2 = range_var;
  f.bearing_var_rad2 = bearing_var;
  f.width_m = width_m;
  return f;
}

TEST(FeatureValidationTest, BadFeaturesAreRejectedCountedAndTheFirstReasonKept) {
  const EstimatorOptions options;  // ranges [0.01, 30] m
  FeatureReading bad_covariance = Feature(5.0, 0.0, 0.01, 0.01);
  bad_covariance.range_bearing_cov_m_rad = 0.02;  // |cov| > sqrt(var_r var_b)
  const std::vector<FeatureReading> features = {
      Feature(31.0, 0.0), Feature(5.0, 0.1), Feature(std::nan(""), 0.0), Feature(5.0, 3.5),
      bad_covariance, Feature(5.0, -0.2, -1.0, 0.01)};
  const ValidatedFeatures v = ValidateFeatures(features, options);
  EXPECT_EQ(v.rejected, 5);
  EXPECT_EQ(v.first_rejection, "range 31.000000 m out of [0.010000, 30.000000] m");
  ASSERT_EQ(v.measurements.size(), 1u);
  EXPECT_EQ(v.measurements[0].range_bearing, Eigen::Vector2d(5.0, 0.1));
  EXPECT_EQ(v.widths_m, std::vector<double>{0.0});
}

TEST(FeatureValidationTest, TheFeaturesOwnCovarianceFlooredOrTheDefaults) {
  EstimatorOptions options;
  options.min_range_sigma_m = 0.05;
  const ValidatedFeatures v = ValidateFeatures(
      {Feature(5.0, 0.0, 0.0001, 0.0004), Feature(5.0, 0.0), Feature(5.0, 0.0, 0.01, 0.0)},
      options);
  ASSERT_EQ(v.measurements.size(), 3u);
  EXPECT_EQ(v.measurements[0].covariance(0, 0), 0.05 * 0.05) << "floored";
  EXPECT_EQ(v.measurements[0].covariance(1, 1), 0.0004);
  const double range_var = options.default_range_sigma_m * options.default_range_sigma_m;
  const double bearing_var = options.default_bearing_sigma_rad * options.default_bearing_sigma_rad;
  for (size_t k : {1u, 2u}) {
    EXPECT_EQ(v.measurements[k].covariance(0, 0), range_var) << "defaults, feature " << k;
    EXPECT_EQ(v.measurements[k].covariance(1, 1), bearing_var);
  }
  options.use_feature_covariance = false;
  EXPECT_EQ(ValidateFeatures({Feature(5.0, 0.0, 0.0001, 0.0004)}, options)
                .measurements[0]
                .covariance(0, 0),
            range_var);
}

TEST(FeatureValidationTest, AFeatureCutByTheEdgeOfALimitedViewGetsMoreUncertainty) {
  EstimatorOptions options;
  options.field_of_view_rad = M_PI;
  // 89.5 degrees, 0.3 m wide at 4 m: its extent reaches the edge at 90 degrees.
  const double at_edge = 89.5 * M_PI / 180.0;
  const ValidatedFeatures v = ValidateFeatures(
      {Feature(4.0, at_edge, 0.01, 0.0001, 0.3), Feature(4.0, 0.0, 0.01, 0.0001, 0.3)}, options);
  EXPECT_EQ(v.at_edge_of_view, 1);
  const double s = options.edge_of_view_sigma_m;
  EXPECT_EQ(v.measurements[0].covariance(0, 0), 0.01 + s * s);
  EXPECT_EQ(v.measurements[0].covariance(1, 1), 0.0001 + (s / 4.0) * (s / 4.0));
  EXPECT_EQ(v.measurements[1].covariance(0, 0), 0.01);
  // Not with a 360-degree view, nor when off.
  options.field_of_view_rad = 2.0 * M_PI;
  EXPECT_EQ(ValidateFeatures({Feature(4.0, M_PI - 0.001, 0.01, 0.0001, 0.3)}, options)
                .at_edge_of_view,
            0);
  options.field_of_view_rad = M_PI;
  options.edge_of_view_sigma_m = 0.0;
  EXPECT_EQ(ValidateFeatures({Feature(4.0, at_edge, 0.01, 0.0001, 0.3)}, options).at_edge_of_view,
            0);
}

TEST(FieldOfViewTest, AnAsymmetricViewHasItsOwnEdges) {
  // A view from -120 to +90 degrees (the robot's body hides the rest).
  const double deg = M_PI / 180.0;
  const FieldOfView view{-120.0 * deg, 90.0 * deg, false};
  EXPECT_FALSE(view.full());
  EXPECT_TRUE(view.ContainsWithMargin(0.0, 0.0));
  EXPECT_TRUE(view.ContainsWithMargin(-110.0 * deg, 5.0 * deg));
  EXPECT_FALSE(view.ContainsWithMargin(-118.0 * deg, 5.0 * deg));
  EXPECT_TRUE(view.Excludes(100.0 * deg));
  EXPECT_FALSE(view.Excludes(89.0 * deg));
  EXPECT_TRUE(view.Excludes(-150.0 * deg));
  EXPECT_TRUE(view.Excludes(M_PI));
  // A view across the back: from 150 to 250 degrees (= -110).
  const FieldOfView back{150.0 * deg, 250.0 * deg, false};
  EXPECT_TRUE(back.ContainsWithMargin(M_PI, 10.0 * deg));
  EXPECT_TRUE(back.ContainsWithMargin(-115.0 * deg, 0.0));
  EXPECT_TRUE(back.Excludes(0.0));
  // The options: start and end given, or the width centred.
  EstimatorOptions options;
  options.field_of_view_start_rad = -120.0 * deg;
  options.field_of_view_end_rad = 90.0 * deg;
  EXPECT_EQ(CheckEstimatorOptions(options), "");
  EXPECT_FALSE(FieldOfViewOf(options).symmetric);
  EXPECT_EQ(FieldOfViewOf(options).start_rad, -120.0 * deg);
  options.field_of_view_rad = M_PI;
  EXPECT_EQ(CheckEstimatorOptions(options),
            "give field_of_view_deg or field_of_view_start_deg / _end_deg, not both");
  options.field_of_view_rad = 2.0 * M_PI;
  options.field_of_view_end_rad = -130.0 * deg;
  EXPECT_NE(CheckEstimatorOptions(options).find("field_of_view_end_deg must be >"),
            std::string::npos);
  EstimatorOptions centred;
  centred.field_of_view_rad = M_PI;
  EXPECT_TRUE(FieldOfViewOf(centred).symmetric);
  EXPECT_EQ(FieldOfViewOf(centred).end_rad, 0.5 * M_PI);
}

TEST(FeatureValidationTest, AFeatureAtAnEdgeOfAnAsymmetricViewGetsMoreUncertainty) {
  const double deg = M_PI / 180.0;
  EstimatorOptions options;
  options.field_of_view_start_rad = -120.0 * deg;
  options.field_of_view_end_rad = 90.0 * deg;
  // Near -120 degrees: at the edge; at +89.5 degrees: at the other edge; at -89.5 (an edge of
  // a symmetric 180-degree view, well inside this one): not.
  const ValidatedFeatures v = ValidateFeatures({Feature(4.0, -119.5 * deg, 0.01, 0.0001, 0.3),
                                                Feature(4.0, 89.5 * deg, 0.01, 0.0001, 0.3),
                                                Feature(4.0, -89.5 * deg, 0.01, 0.0001, 0.3)},
                                               options);
  EXPECT_EQ(v.at_edge_of_view, 2);
  EXPECT_GT(v.measurements[0].covariance(0, 0), 0.01);
  EXPECT_GT(v.measurements[1].covariance(0, 0), 0.01);
  EXPECT_EQ(v.measurements[2].covariance(0, 0), 0.01);
}

TEST(ScanGatingTest, KeepsPairsUpToTheWidestGateAndJUnderD1) {
  testing::StepScene scene;
  const int landmark = scene.AddLandmark({5.0, 0.0}, 0.05);
  scene.Measure({5.02, 0.0});   // NIS about 0.1: in J
  scene.Measure({5.18, 0.0});   // NIS about 9.5: between d1 and d2
  scene.Measure({5.24, 0.0});   // NIS about 17: between d2 and dn
  scene.Measure({5.5, 0.0});    // NIS about 74: outside every gate
  const std::vector<ObjectPrediction> predictions = scene.Predictions();
  const ScanGating gating = GateScan(scene.measurements, predictions, scene.options);
  ASSERT_EQ(gating.gated.size(), 3u);
  for (const Candidate& c : gating.gated) {
    EXPECT_EQ(c.object, landmark);
    EXPECT_EQ(c.nis, scene.Nis(c.measurement, landmark));
  }
  ASSERT_EQ(gating.compatible.size(), 1u);
  EXPECT_EQ(gating.compatible[0].measurement, 0);
  ASSERT_EQ(gating.nearest_nis.size(), 4u);
  EXPECT_EQ(gating.nearest_nis[2], scene.Nis(2, landmark));
  EXPECT_EQ(gating.nearest_nis[3], std::numeric_limits<double>::infinity());
  // A gate dn below d2 and level 3 off: the widest gate is d1 or dn.
  scene.options.level3 = false;
  scene.options.new_object_gate_dn_chi2 = 10.0;
  EXPECT_EQ(GateScan(scene.measurements, predictions, scene.options).gated.size(), 2u);
}

}  // namespace
}  // namespace slammtt
