#include "perception/leg_likeness.h"

#include <algorithm>
#include <cmath>

namespace slammtt {
namespace {

// 1 on [low, high], linear to 0 at low - margin_below and at high + margin_above.
double Trapezoid(double d, double low, double high, double margin_below, double margin_above) {
  if (d < low) return std::max(0.0, 1.0 - (low - d) / margin_below);
  if (d > high) return std::max(0.0, 1.0 - (d - high) / margin_above);
  return 1.0;
}

double StandardNormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

ClusterShape DescribeClusterShape(const ClusterView& cluster, double spacing_rad) {
  ClusterShape shape;
  const size_t n = cluster.count;
  shape.num_points = n;
  shape.first_edge_occluded = cluster.first_edge_occluded;
  shape.last_edge_occluded = cluster.last_edge_occluded;
  if (n == 0) return shape;
  double sum_r = 0.0;
  for (size_t i = 0; i < n; ++i) sum_r += cluster.range_m[i];
  shape.mean_range_m = sum_r / static_cast<double>(n);
  shape.extent_rad = cluster.bearing_rad[n - 1] - cluster.bearing_rad[0];
  shape.spacing_rad = n > 1 ? shape.extent_rad / static_cast<double>(n - 1) : spacing_rad;
  shape.diameter_low_m = shape.mean_range_m * shape.extent_rad;
  shape.diameter_high_m = shape.mean_range_m * (shape.extent_rad + 2.0 * shape.spacing_rad);
  if (n >= 3) {
    // Unit normal of the chord, pointing to the sensor's side (the origin).
    const double ax = cluster.x_m[0];
    const double ay = cluster.y_m[0];
    const double dx = cluster.x_m[n - 1] - ax;
    const double dy = cluster.y_m[n - 1] - ay;
    const double length = std::sqrt(dx * dx + dy * dy);
    if (length > 1e-12) {
      double nx = -dy / length;
      double ny = dx / length;
      if (nx * -ax + ny * -ay < 0.0) {
        nx = -nx;
        ny = -ny;
      }
      // The middle half of the interior points (at least the middle one).
      const size_t begin = std::max<size_t>(1, n / 4);
      const size_t end = std::max(begin + 1, std::min(n - 1, n - n / 4));
      double sum = 0.0;
      for (size_t i = begin; i < end; ++i) {
        sum += (cluster.x_m[i] - ax) * nx + (cluster.y_m[i] - ay) * ny;
      }
      shape.bulge_m = sum / static_cast<double>(end - begin);
      shape.bulge_points = end - begin;
    }
  }
  return shape;
}

double LegLikeness(const ClusterShape& shape, const LegLikenessOptions& options,
                   double sigma_r_m) {
  if (shape.num_points == 0 || !std::isfinite(shape.diameter_low_m) ||
      !std::isfinite(shape.diameter_high_m) || !std::isfinite(shape.bulge_m)) {
    return 0.0;
  }
  // Width: mean of the trapezoid over the interval holding the diameter (8 midpoints).
  const double margin = options.diameter_margin_m;
  const double low = shape.diameter_low_m;
  const double high = std::max(shape.diameter_high_m, low);
  constexpr int kSamples = 8;
  double width = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double d = low + (high - low) * (k + 0.5) / kSamples;
    width += Trapezoid(d, options.min_diameter_m, options.max_diameter_m, margin,
                       3.0 * margin);
  }
  width /= kSamples;
  if (width <= 0.0) return 0.0;

  // Two points: no curvature to see, halfway between flat and round.
  double convexity = 0.5 * (1.0 + options.convexity_floor);
  if (shape.bulge_points > 0) {
    const double diameter = shape.mean_range_m * (shape.extent_rad + shape.spacing_rad);
    if (!(diameter > 0.0)) return 0.0;
    const double half = 0.5 * diameter;
    const double c = shape.bulge_m / half;
    const double sigma_bulge2 = sigma_r_m * sigma_r_m *
                                (1.0 / static_cast<double>(shape.bulge_points) + 0.5);
    const double sigma_c2 = sigma_bulge2 / (half * half);
    const double b = options.convexity_floor;
    convexity = b + (1.0 - b) * StandardNormalCdf((c - 0.2) / std::sqrt(sigma_c2 + 0.01));
  }

  const int occluded = static_cast<int>(shape.first_edge_occluded) +
                       static_cast<int>(shape.last_edge_occluded);
  const double edges = occluded == 0 ? 1.0 : (occluded == 1 ? 0.85 : 0.5);
  const double score = width * convexity * edges;
  return std::isfinite(score) ? std::clamp(score, 0.0, 1.0) : 0.0;
}

}  // namespace slammtt
