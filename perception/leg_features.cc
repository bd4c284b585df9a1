#include "perception/leg_features.h"

#include <algorithm>
#include <cmath>

#include "perception/line_extraction.h"

namespace slammtt {

const std::array<const char*, kNumLegFeatures> kLegFeatureNames = {
    "points",          "range_m",         "beam_gap_m",      "width_m",
    "std_dev_m",       "mad_median_m",    "jump_before_m",    "jump_after_m",
    "line_rms_m",      "circle_rms_m",    "circle_radius_m",  "boundary_length_m",
    "boundary_regularity_m", "mean_curvature_1pm", "mean_turn_rad", "convexity",
};

namespace {

double Jump(double neighbour_range_m, double edge_range_m) {
  if (!std::isfinite(neighbour_range_m)) return kLegJumpCapM;
  return std::clamp(neighbour_range_m - edge_range_m, -kLegJumpCapM, kLegJumpCapM);
}

// Median of values[0, n) (n >= 1), reordering them.
double MedianOf(double* values, size_t n) {
  const size_t middle = n / 2;
  std::nth_element(values, values + middle, values + n);
  const double upper = values[middle];
  if (n % 2 == 1) return upper;
  const double lower = *std::max_element(values, values + middle);
  return 0.5 * (lower + upper);
}

// Bulge of the middle half of the points in front of the chord (leg_likeness.h's cue).
double Bulge(const ClusterView& c) {
  const size_t n = c.count;
  if (n < 3) return 0.0;
  const double ax = c.x_m[0];
  const double ay = c.y_m[0];
  const double dx = c.x_m[n - 1] - ax;
  const double dy = c.y_m[n - 1] - ay;
  const double length = std::sqrt(dx * dx + dy * dy);
  if (!(length > 1e-12)) return 0.0;
  double nx = -dy / length;
  double ny = dx / length;
  if (nx * -ax + ny * -ay < 0.0) {  // towards the sensor
    nx = -nx;
    ny = -ny;
  }
  const size_t begin = std::max<size_t>(1, n / 4);
  const size_t end = std::max(begin + 1, std::min(n - 1, n - n / 4));
  double sum = 0.0;
  for (size_t i = begin; i < end; ++i) sum += (c.x_m[i] - ax) * nx + (c.y_m[i] - ay) * ny;
  return sum / static_cast<double>(end - begin);
}

}  // namespace

LegFeatureVector ComputeLegFeatures(const ClusterView& c, const ClusterSurroundings& around) {
  std::array<double, kNumLegFeatures> f{};
  const size_t n = c.count;
  if (n == 0) return LegFeatureVector{};
  const double count = static_cast<double>(n);
  f[kPoints] = count;
  double sum_r = 0.0;
  for (size_t i = 0; i < n; ++i) sum_r += c.range_m[i];
  const double mean_range = sum_r / count;
  f[kRange] = mean_range;
  const double extent = c.bearing_rad[n - 1] - c.bearing_rad[0];
  const double spacing = n > 1 ? extent / (count - 1.0) : around.scan_spacing_rad;
  f[kBeamGap] = mean_range * spacing;
  f[kWidth] = std::hypot(c.x_m[n - 1] - c.x_m[0], c.y_m[n - 1] - c.y_m[0]);

  double mx = 0.0;
  double my = 0.0;
  for (size_t i = 0; i < n; ++i) {
    mx += c.x_m[i];
    my += c.y_m[i];
  }
  mx /= count;
  my /= count;
  double sum_d2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sum_d2 += (c.x_m[i] - mx) * (c.x_m[i] - mx) + (c.y_m[i] - my) * (c.y_m[i] - my);
  }
  f[kStdDev] = std::sqrt(sum_d2 / count);

  // Coordinate-wise median: small clusters only reach here in practice (max_width_m), but the
  // scratch space must not allocate per call: medians of at most 64 points are exact, larger
  // clusters use every k-th point.
  constexpr size_t kMaxMedianPoints = 64;
  std::array<double, kMaxMedianPoints> xs{};
  std::array<double, kMaxMedianPoints> ys{};
  const size_t stride = (n + kMaxMedianPoints - 1) / kMaxMedianPoints;
  size_t m = 0;
  for (size_t i = 0; i < n && m < kMaxMedianPoints; i += stride, ++m) {
    xs[m] = c.x_m[i];
    ys[m] = c.y_m[i];
  }
  const double median_x = MedianOf(xs.data(), m);
  const double median_y = MedianOf(ys.data(), m);
  double sum_dev = 0.0;
  for (size_t i = 0; i < n; ++i) sum_dev += std::hypot(c.x_m[i] - median_x, c.y_m[i] - median_y);
  f[kMadMedian] = sum_dev / count;

  f[kJumpBefore] = Jump(around.range_before_m, c.range_m[0]);
  f[kJumpAfter] = Jump(around.range_after_m, c.range_m[n - 1]);

  if (n >= 2) {
    f[kLineRms] = FitLine(c.x_m, c.y_m, n, 0.01, 0.01).rms_residual_m;
    double length = 0.0;
    double length2 = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) {
      const double d = std::hypot(c.x_m[i + 1] - c.x_m[i], c.y_m[i + 1] - c.y_m[i]);
      length += d;
      length2 += d * d;
    }
    f[kBoundaryLength] = length;
    const double steps = count - 1.0;
    f[kBoundaryRegularity] = std::sqrt(std::max(0.0, length2 / steps - (length / steps) *
                                                                          (length / steps)));
  }
  const CircleFit circle = FitCircleKasa(c.x_m, c.y_m, n);
  f[kCircleRms] = circle.ok ? circle.rms_residual_m : f[kLineRms];
  f[kCircleRadius] = circle.ok ? std::min(circle.radius_m, kLegRadiusCapM) : kLegRadiusCapM;

  if (n >= 3) {
    double curvature = 0.0;
    double turn = 0.0;
    for (size_t i = 1; i + 1 < n; ++i) {
      const double ux = c.x_m[i] - c.x_m[i - 1];
      const double uy = c.y_m[i] - c.y_m[i - 1];
      const double vx = c.x_m[i + 1] - c.x_m[i];
      const double vy = c.y_m[i + 1] - c.y_m[i];
      // Counter-clockwise points on an outline that bulges towards the sensor turn clockwise:
      // the cross product is negative there, hence the minus signs.
      const double cross = ux * vy - uy * vx;
      const double dot = ux * vx + uy * vy;
      const double a = std::hypot(ux, uy);
      const double b = std::hypot(vx, vy);
      const double chord = std::hypot(c.x_m[i + 1] - c.x_m[i - 1], c.y_m[i + 1] - c.y_m[i - 1]);
      const double denominator = a * b * chord;
      if (denominator > 1e-12) curvature += -2.0 * cross / denominator;
      turn += -std::atan2(cross, dot);
    }
    f[kMeanCurvature] = curvature / (count - 2.0);
    f[kMeanTurn] = turn / (count - 2.0);
    const double diameter = mean_range * (extent + spacing);
    if (diameter > 0.0) f[kConvexity] = Bulge(c) / (0.5 * diameter);
  }

  LegFeatureVector out{};
  for (int k = 0; k < kNumLegFeatures; ++k) {
    const float value = static_cast<float>(f[k]);
    out[k] = std::isfinite(value) ? value : 0.0f;
  }
  return out;
}

}  // namespace slammtt
