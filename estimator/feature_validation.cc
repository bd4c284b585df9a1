#include "estimator/feature_validation.h"

#include <algorithm>
#include <cmath>

#include "common/angle.h"

namespace slammtt {
namespace {

// Why a feature cannot be used ("" when it can).
std::string RejectionReason(const FeatureReading& f, const EstimatorOptions& options) {
  if (!std::isfinite(f.range_m) || !std::isfinite(f.bearing_rad) ||
      !std::isfinite(f.range_var_m2) || !std::isfinite(f.bearing_var_rad2) ||
      !std::isfinite(f.range_bearing_cov_m_rad)) {
    return "not finite";
  }
  if (f.range_m < options.min_range_m || f.range_m > options.max_range_m) {
    return "range " + std::to_string(f.range_m) + " m out of [" +
           std::to_string(options.min_range_m) + ", " + std::to_string(options.max_range_m) +
           "] m";
  }
  if (std::abs(f.bearing_rad) > M_PI + 1e-9) {
    return "bearing " + std::to_string(f.bearing_rad) + " rad out of [-pi, pi]";
  }
  if (f.range_var_m2 < 0.0 || f.bearing_var_rad2 < 0.0 ||
      f.range_bearing_cov_m_rad * f.range_bearing_cov_m_rad >
          f.range_var_m2 * f.bearing_var_rad2) {
    return "covariance not positive semi-definite";
  }
  return "";
}

// The measurement of an accepted feature, R from the feature or the defaults.
PointMeasurement MeasurementOf(const FeatureReading& f, const EstimatorOptions& options) {
  PointMeasurement m;
  m.range_bearing = Eigen::Vector2d(f.range_m, WrapAngle(f.bearing_rad));
  m.person = f.person;
  m.pair_confidence = f.pair_confidence;
  if (options.use_feature_covariance && f.range_var_m2 > 0.0 && f.bearing_var_rad2 > 0.0) {
    m.covariance << f.range_var_m2, f.range_bearing_cov_m_rad, f.range_bearing_cov_m_rad,
        f.bearing_var_rad2;
    m.covariance(0, 0) =
        std::max(m.covariance(0, 0), options.min_range_sigma_m * options.min_range_sigma_m);
    m.covariance(1, 1) = std::max(m.covariance(1, 1),
                                  options.min_bearing_sigma_rad * options.min_bearing_sigma_rad);
  } else {
    const double range_var = options.default_range_sigma_m * options.default_range_sigma_m;
    const double bearing_var =
        options.default_bearing_sigma_rad * options.default_bearing_sigma_rad;
    m.covariance << range_var, 0.0, 0.0, bearing_var;
  }
  return m;
}

// Inflates R of a feature cut by the edge of a limited field of view; true when it did.
bool InflateAtEdgeOfView(double width_m, const EstimatorOptions& options, PointMeasurement* m) {
  const FieldOfView view = FieldOfViewOf(options);
  if (!(options.edge_of_view_sigma_m > 0.0 && !view.full())) return false;
  const double range = m->range_bearing(0);
  const double extent = std::atan2(0.5 * width_m, range);
  // (A symmetric view: the expression of old, term for term, so the sums round the same.)
  const bool inside =
      view.symmetric
          ? std::abs(m->range_bearing(1)) + extent + kEdgeOfViewMargin_rad < view.end_rad
          : view.ContainsWithMargin(m->range_bearing(1), extent + kEdgeOfViewMargin_rad);
  if (inside) return false;
  const double s = options.edge_of_view_sigma_m;
  // s across the line of sight is s / range in bearing, at most pi: a bearing cannot be more
  // uncertain than the half circle, and a feature at the sensor (min_range_m 0) must not get
  // an infinite variance.
  const double bearing_sigma = std::min(s / range, M_PI);
  m->covariance(0, 0) += s * s;
  m->covariance(1, 1) += bearing_sigma * bearing_sigma;
  return true;
}

// At most `cap` measurements: the nearest (ties: earlier), kept in their order.
void KeepNearest(size_t cap, ValidatedFeatures* validated) {
  const size_t n = validated->measurements.size();
  if (n <= cap) return;
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  const auto nearer = [&](size_t a, size_t b) {
    const double ra = validated->measurements[a].range_bearing(0);
    const double rb = validated->measurements[b].range_bearing(0);
    return ra < rb || (ra == rb && a < b);
  };
  std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(cap), order.end(),
                   nearer);
  order.resize(cap);
  std::sort(order.begin(), order.end());
  std::vector<PointMeasurement> measurements;
  std::vector<double> widths;
  measurements.reserve(cap);
  widths.reserve(cap);
  for (size_t k : order) {
    measurements.push_back(validated->measurements[k]);
    widths.push_back(validated->widths_m[k]);
  }
  validated->measurements.swap(measurements);
  validated->widths_m.swap(widths);
  validated->over_cap = static_cast<int>(n - cap);
}

}  // namespace

ValidatedFeatures ValidateFeatures(const std::vector<FeatureReading>& features,
                                   const EstimatorOptions& options) {
  ValidatedFeatures validated;
  validated.measurements.reserve(features.size());
  for (const FeatureReading& f : features) {
    const std::string reason = RejectionReason(f, options);
    if (!reason.empty()) {
      ++validated.rejected;
      if (validated.first_rejection.empty()) validated.first_rejection = reason;
      continue;
    }
    PointMeasurement m = MeasurementOf(f, options);
    const double width = std::isfinite(f.width_m) && f.width_m > 0.0 ? f.width_m : 0.0;
    if (InflateAtEdgeOfView(width, options, &m)) ++validated.at_edge_of_view;
    validated.measurements.push_back(m);
    validated.widths_m.push_back(width);
  }
  KeepNearest(static_cast<size_t>(options.max_features_per_scan), &validated);
  return validated;
}

}  // namespace slammtt
