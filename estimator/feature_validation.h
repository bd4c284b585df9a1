// The features of one scan as the estimator takes them (before Algorithm 2): every feature
// checked, the accepted ones turned into range-bearing measurements with their covariance R
// (paper eq. 14).
//
//  - Rejected, counted, and the first reason kept: a non-finite value, a range outside
//    [min_range_m, max_range_m], a bearing outside [-pi, pi], a covariance that is not positive
//    semi-definite.
//  - R is the feature's own covariance when use_feature_covariance is set and it carries one
//    (both variances > 0), floored at min_range_sigma_m / min_bearing_sigma_rad; otherwise the
//    defaults (default_range_sigma_m, default_bearing_sigma_rad, paper section 5.1).
//  - A feature cut by the edge of a limited field of view (its angular extent, atan(width / 2 /
//    range) either side of its bearing, within kEdgeOfViewMargin_rad of the edge) gets
//    edge_of_view_sigma_m^2 added to its range variance and min(s / range, pi)^2 to its bearing
//    variance (estimator_options.h).
//  - Of the accepted features, at most max_features_per_scan are kept: the nearest (ties:
//    input order), in their input order; the others are counted (over_cap).
#pragma once

#include <string>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/point_measurement.h"

namespace slammtt {

// One feature_t as received.
struct FeatureReading {
  double range_m = 0.0;
  double bearing_rad = 0.0;
  double range_var_m2 = 0.0;   // 0 (with bearing_var 0): use the default noise
  double bearing_var_rad2 = 0.0;
  double range_bearing_cov_m_rad = 0.0;
  double width_m = 0.0;        // extent of the cluster (0: a point), for occlusion reasoning
  bool person = false;         // a person feature's centre (people.h), not a point feature
  // A person feature of two legs: perception's confidence that it is a person (0: one leg, or
  // not a person feature; people.h, report_pair_births_confidence).
  double pair_confidence = 0.0;
};

struct ValidatedFeatures {
  std::vector<PointMeasurement> measurements;  // the accepted features, in their order
  std::vector<double> widths_m;                // of each accepted feature (>= 0, finite)
  int rejected = 0;
  std::string first_rejection;                 // why the first rejected feature was rejected
  int at_edge_of_view = 0;                     // accepted features whose R was inflated
  int over_cap = 0;                            // accepted, but beyond max_features_per_scan
};

ValidatedFeatures ValidateFeatures(const std::vector<FeatureReading>& features,
                                   const EstimatorOptions& options);

}  // namespace slammtt
