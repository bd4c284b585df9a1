#include "perception/centre_estimation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace slammtt {
namespace {

// An angle expressed near `reference` (within pi of it), for the unwrapped bearing frame.
double NearAngle(double angle_rad, double reference_rad) {
  return reference_rad + std::remainder(angle_rad - reference_rad, 2.0 * M_PI);
}

// Mean of the per-point centre distances D_i = a_i + sqrt(R^2 - c_i^2) along the unit ray
// (ux, uy) for a circle of fixed radius R, weighted by (R^2 - c_i^2) / R^2.
double CentreDistanceForRadius(const ClusterView& cluster, double ux, double uy,
                               double radius_m) {
  const double r2 = radius_m * radius_m;
  double sum_w = 0.0;
  double sum_wd = 0.0;
  double sum_a = 0.0;
  for (size_t i = 0; i < cluster.count; ++i) {
    const double a = cluster.x_m[i] * ux + cluster.y_m[i] * uy;
    const double c = -cluster.x_m[i] * uy + cluster.y_m[i] * ux;
    const double q = r2 - c * c;
    sum_a += a;
    if (q <= 0.0) continue;
    const double w = q / r2;
    sum_w += w;
    sum_wd += w * (a + std::sqrt(q));
  }
  if (sum_w > 0.0) return sum_wd / sum_w;
  return sum_a / static_cast<double>(cluster.count) + radius_m;  // every point off the circle
}

}  // namespace

CentreEstimate MiddlePointCentre(const ClusterView& cluster) {
  CentreEstimate estimate;
  const size_t n = cluster.count;
  if (n % 2 == 1) {
    estimate.range_m = cluster.range_m[n / 2];
    estimate.bearing_rad = cluster.bearing_rad[n / 2];
    return estimate;
  }
  const size_t i = n / 2 - 1;
  const size_t j = n / 2;
  const double x = 0.5 * (cluster.x_m[i] + cluster.x_m[j]);
  const double y = 0.5 * (cluster.y_m[i] + cluster.y_m[j]);
  estimate.range_m = std::hypot(x, y);
  const double middle = 0.5 * (cluster.bearing_rad[i] + cluster.bearing_rad[j]);
  estimate.bearing_rad = estimate.range_m > 0.0 ? NearAngle(std::atan2(y, x), middle) : middle;
  return estimate;
}

CentreEstimate RadiusCorrectedCentre(const ClusterView& cluster, double max_radius_m) {
  CentreEstimate estimate;
  const size_t n = cluster.count;
  if (n == 1) {
    estimate.range_m = cluster.range_m[0];
    estimate.bearing_rad = cluster.bearing_rad[0];
    return estimate;
  }
  const double first = cluster.bearing_rad[0];
  const double last = cluster.bearing_rad[n - 1];
  const double spacing = (last - first) / static_cast<double>(n - 1);
  const double alpha = (last - first) + spacing;
  const double centre_bearing = 0.5 * (first + last);
  const double ux = std::cos(centre_bearing);
  const double uy = std::sin(centre_bearing);
  // An extent near pi would put the centre at infinity; the radius clamp below takes over.
  const double s = std::min(std::sin(0.5 * std::min(alpha, M_PI)), 0.99);
  const double s2 = s * s;

  double sum_w = 0.0;
  double sum_wd = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double r = cluster.range_m[i];
    const double a = cluster.x_m[i] * ux + cluster.y_m[i] * uy;  // r cos(phi)
    const double c = -cluster.x_m[i] * uy + cluster.y_m[i] * ux;  // r sin(phi)
    const double q = s2 * r * r - c * c;
    if (q <= 0.0) continue;  // at or beyond the estimated tangent: weight 0
    const double w = q / (s2 * r * r);
    sum_w += w;
    sum_wd += w * (a + std::sqrt(q)) / (1.0 - s2);
  }
  double distance = 0.0;
  if (sum_w > 0.0) {
    distance = sum_wd / sum_w;
  } else {
    // Cannot happen for a cluster with increasing bearings (its middle is inside the extent);
    // kept so that a degenerate input still gives a finite answer.
    distance = cluster.range_m[n / 2] / (1.0 - s);
  }
  double radius = distance * s;
  if (radius > max_radius_m) {
    radius = max_radius_m;
    distance = CentreDistanceForRadius(cluster, ux, uy, radius);
  }
  estimate.range_m = distance;
  estimate.bearing_rad = centre_bearing;
  estimate.radius_m = radius;
  return estimate;
}

FitCircle::FitCircle(double distance, double bearing, double radius)
    : distance_m(distance),
      bearing_rad(bearing),
      radius_m(radius),
      cos_bearing(std::cos(bearing)),
      sin_bearing(std::sin(bearing)),
      centre_x_m(distance * cos_bearing),
      centre_y_m(distance * sin_bearing) {
  const double root = std::sqrt(distance * distance - radius * radius);
  half_angle_rad = std::asin(radius / distance);
  d_half_angle_d_distance = -radius / (distance * root);
  d_half_angle_d_radius = 1.0 / root;
}

bool CirclePointResidual(const FitCircle& circle, double x_m, double y_m, double* residual_m,
                         Eigen::Vector3d* jacobian) {
  const double dx = circle.centre_x_m - x_m;
  const double dy = circle.centre_y_m - y_m;
  const double d = std::sqrt(dx * dx + dy * dy);
  if (!(d > 0.0)) return false;
  const double inv_d = 1.0 / d;
  const double ux = dx * inv_d;
  const double uy = dy * inv_d;
  *jacobian = Eigen::Vector3d(ux * circle.cos_bearing + uy * circle.sin_bearing,
                              circle.distance_m * (-ux * circle.sin_bearing +
                                                   uy * circle.cos_bearing),
                              -1.0);
  *residual_m = d - circle.radius_m;
  return true;
}

double CircleTangentBearing(const FitCircle& circle, int side, Eigen::Vector3d* jacobian) {
  if (side < 0) {
    *jacobian = Eigen::Vector3d(-circle.d_half_angle_d_distance, 1.0,
                                -circle.d_half_angle_d_radius);
    return circle.bearing_rad - circle.half_angle_rad;
  }
  *jacobian = Eigen::Vector3d(circle.d_half_angle_d_distance, 1.0, circle.d_half_angle_d_radius);
  return circle.bearing_rad + circle.half_angle_rad;
}

CentreEstimate CircleFitCentre(const ClusterView& cluster, double max_radius_m, double sigma_r_m) {
  CentreEstimate fallback = RadiusCorrectedCentre(cluster, max_radius_m);
  fallback.fell_back = true;
  const size_t n = cluster.count;
  if (n < 2) return fallback;
  const bool use_first = !cluster.first_edge_occluded;
  const bool use_last = !cluster.last_edge_occluded;
  const size_t tangents = static_cast<size_t>(use_first) + static_cast<size_t>(use_last);
  if (n + tangents < 3 || (tangents == 0 && n < kMinCircleFitPoints)) return fallback;

  const double first = cluster.bearing_rad[0];
  const double last = cluster.bearing_rad[n - 1];
  const double spacing = (last - first) / static_cast<double>(n - 1);
  const double first_tangent = first - 0.5 * spacing;
  const double last_tangent = last + 0.5 * spacing;
  const double inv_sigma_t = std::sqrt(12.0) / spacing;
  const double inv_sigma_r = 1.0 / sigma_r_m;

  double distance = fallback.range_m;
  double bearing = fallback.bearing_rad;
  double radius = std::max(fallback.radius_m, 1e-3);
  // One step from a consistent start when both tangents are there; otherwise the start is
  // biased (the extent is cut by the occluder) and the fit iterates to convergence.
  const int max_steps = tangents == 2 ? 1 : 3;
  for (int iteration = 0; iteration < max_steps; ++iteration) {
    const FitCircle circle(distance, bearing, radius);
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();  // J^T J over (D, theta, R)
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // J^T e
    auto add = [&](const Eigen::Vector3d& jacobian, double residual) {
      normal.noalias() += jacobian * jacobian.transpose();
      gradient.noalias() += jacobian * residual;
    };
    for (size_t i = 0; i < n; ++i) {
      double residual = 0.0;
      Eigen::Vector3d jacobian;
      if (!CirclePointResidual(circle, cluster.x_m[i], cluster.y_m[i], &residual, &jacobian)) {
        return fallback;  // centre on a point: no gradient
      }
      add(jacobian * inv_sigma_r, residual * inv_sigma_r);
    }
    if (use_first) {
      Eigen::Vector3d jacobian;
      const double tangent = CircleTangentBearing(circle, -1, &jacobian);
      add(jacobian * inv_sigma_t, (tangent - first_tangent) * inv_sigma_t);
    }
    if (use_last) {
      Eigen::Vector3d jacobian;
      const double tangent = CircleTangentBearing(circle, 1, &jacobian);
      add(jacobian * inv_sigma_t, (tangent - last_tangent) * inv_sigma_t);
    }
    // Symmetric 3x3 solve by cofactors; refused when the system is near singular relative to
    // its diagonal (det <= product of the diagonal for a positive semi-definite matrix).
    const double a00 = normal(0, 0), a01 = normal(0, 1), a02 = normal(0, 2);
    const double a11 = normal(1, 1), a12 = normal(1, 2), a22 = normal(2, 2);
    const double c00 = a11 * a22 - a12 * a12;
    const double c01 = a02 * a12 - a01 * a22;
    const double c02 = a01 * a12 - a02 * a11;
    const double c11 = a00 * a22 - a02 * a02;
    const double c12 = a01 * a02 - a00 * a12;
    const double c22 = a00 * a11 - a01 * a01;
    const double det = a00 * c00 + a01 * c01 + a02 * c02;
    if (!(det > 1e-12 * a00 * a11 * a22)) return fallback;
    const double g0 = gradient(0), g1 = gradient(1), g2 = gradient(2);
    const Eigen::Vector3d step(-(c00 * g0 + c01 * g1 + c02 * g2) / det,
                               -(c01 * g0 + c11 * g1 + c12 * g2) / det,
                               -(c02 * g0 + c12 * g1 + c22 * g2) / det);
    if (!step.allFinite()) return fallback;
    const double previous_distance = distance;
    const double previous_bearing = bearing;
    const double previous_radius = radius;
    distance += step(0);
    bearing += step(1);
    radius += step(2);
    // Stay in the admissible region: a positive radius, the sensor outside the object.
    if (!(distance > 0.0)) return fallback;
    radius = std::clamp(radius, 1e-4, std::min(max_radius_m, 0.99 * distance));
    // Converged when nothing moves by more than 0.1 mm, far below any range noise.
    if (std::abs(distance - previous_distance) < 1e-4 &&
        std::abs(radius - previous_radius) < 1e-4 &&
        std::abs(bearing - previous_bearing) * distance < 1e-4) {
      break;
    }
  }
  if (!std::isfinite(distance) || !std::isfinite(bearing)) return fallback;
  CentreEstimate estimate;
  estimate.range_m = distance;
  estimate.bearing_rad = bearing;
  estimate.radius_m = radius;
  return estimate;
}

}  // namespace slammtt
