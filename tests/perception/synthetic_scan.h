// A small, independent ray caster for the perception unit tests: circles and straight
// segments seen from a sensor at the origin. Deliberately not the world library, so that the
// segmenter's unit tests check it against geometry written here, not against another module's
// conventions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "perception/scan_view.h"

namespace slammtt {
namespace testing_support {

struct Circle {
  double x_m;
  double y_m;
  double radius_m;
};

struct WallSegment {
  double x0_m;
  double y0_m;
  double x1_m;
  double y1_m;
};

struct TestScan {
  std::vector<float> angle_rad;
  std::vector<float> range_m;
  std::vector<int8_t> valid;
  double range_min_m = 0.05;
  double range_max_m = 12.0;
  ScanView View() const {
    ScanView view = MakeScanView(angle_rad, range_m, valid);
    view.range_min_m = range_min_m;
    view.range_max_m = range_max_m;
    return view;
  }
  size_t size() const { return angle_rad.size(); }
};

// n angles from first_rad, step fov_rad / n (a 360-degree scan: fov 2 pi, no repeated beam).
inline std::vector<double> EvenAngles(double first_rad, double fov_rad, int n, bool closed) {
  std::vector<double> angles(static_cast<size_t>(n));
  const double step = closed ? fov_rad / n : fov_rad / (n - 1);
  for (int i = 0; i < n; ++i) angles[static_cast<size_t>(i)] = first_rad + step * i;
  return angles;
}

// Range from the origin along angle to the circle's near side, or a negative value on a miss.
inline double RayCircle(double angle_rad, const Circle& c) {
  const double ux = std::cos(angle_rad);
  const double uy = std::sin(angle_rad);
  const double along = c.x_m * ux + c.y_m * uy;
  const double across = -c.x_m * uy + c.y_m * ux;
  const double q = c.radius_m * c.radius_m - across * across;
  if (q < 0.0 || along <= 0.0) return -1.0;
  return along - std::sqrt(q);
}

// Range from the origin along angle to the segment, or a negative value on a miss.
inline double RaySegment(double angle_rad, const WallSegment& w) {
  const double ux = std::cos(angle_rad);
  const double uy = std::sin(angle_rad);
  const double ex = w.x1_m - w.x0_m;
  const double ey = w.y1_m - w.y0_m;
  const double denominator = ux * ey - uy * ex;
  if (std::abs(denominator) < 1e-12) return -1.0;
  const double t = (w.x0_m * ey - w.y0_m * ex) / denominator;      // along the ray
  const double s = (w.x0_m * uy - w.y0_m * ux) / denominator;      // along the segment
  if (t <= 0.0 || s < 0.0 || s > 1.0) return -1.0;
  return t;
}

// Casts every angle against every circle and segment (first hit); no hit or beyond range_max:
// valid 0. Range noise sigma0 + sigma_per_m * range (Gaussian) when rng is given. A beam whose
// neighbour (previous angle) hit a surface more than 0.3 m away in range becomes a mixed pixel
// with probability mixed_probability: a range uniformly between the two.
inline TestScan CastScene(const std::vector<Circle>& circles,
                          const std::vector<WallSegment>& segments,
                          const std::vector<double>& angles, double range_max_m,
                          double sigma0_m, double sigma_per_m, std::mt19937_64* rng,
                          double mixed_probability = 0.0) {
  TestScan scan;
  scan.range_max_m = range_max_m;
  std::normal_distribution<double> unit_noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> truth(angles.size(), -1.0);
  for (size_t i = 0; i < angles.size(); ++i) {
    double best = -1.0;
    for (const Circle& c : circles) {
      const double r = RayCircle(angles[i], c);
      if (r > 0.0 && (best < 0.0 || r < best)) best = r;
    }
    for (const WallSegment& w : segments) {
      const double r = RaySegment(angles[i], w);
      if (r > 0.0 && (best < 0.0 || r < best)) best = r;
    }
    truth[i] = best;
  }
  for (size_t i = 0; i < angles.size(); ++i) {
    double r = truth[i];
    const double neighbour = i > 0 ? truth[i - 1] : -1.0;
    if (rng != nullptr && r > 0.0 && neighbour > 0.0 && std::abs(neighbour - r) > 0.3 &&
        uniform(*rng) < mixed_probability) {
      r = std::min(r, neighbour) + uniform(*rng) * std::abs(neighbour - r);
    }
    if (r > 0.0 && rng != nullptr) r += (sigma0_m + sigma_per_m * r) * unit_noise(*rng);
    const bool hit = r > 0.0 && r <= range_max_m;
    scan.angle_rad.push_back(static_cast<float>(angles[i]));
    scan.range_m.push_back(hit ? static_cast<float>(r) : 0.0f);
    scan.valid.push_back(hit ? 1 : 0);
  }
  return scan;
}

// Casts every angle against every circle (first hit); no hit or beyond range_max: valid 0,
// range 0 (as the RPLIDAR reports it). Gaussian range noise when sigma > 0 and rng given.
inline TestScan CastScan(const std::vector<Circle>& circles, const std::vector<double>& angles,
                         double range_max_m = 12.0, double range_sigma_m = 0.0,
                         std::mt19937_64* rng = nullptr) {
  TestScan scan;
  scan.range_max_m = range_max_m;
  std::normal_distribution<double> noise(0.0, range_sigma_m > 0.0 ? range_sigma_m : 1.0);
  for (double angle : angles) {
    double best = -1.0;
    for (const Circle& c : circles) {
      const double r = RayCircle(angle, c);
      if (r > 0.0 && (best < 0.0 || r < best)) best = r;
    }
    if (best > 0.0 && rng != nullptr && range_sigma_m > 0.0) best += noise(*rng);
    const bool hit = best > 0.0 && best <= range_max_m;
    scan.angle_rad.push_back(static_cast<float>(angle));
    scan.range_m.push_back(hit ? static_cast<float>(best) : 0.0f);
    scan.valid.push_back(hit ? 1 : 0);
  }
  return scan;
}

// Beams of `circles` that hit circle i first (for expectations).
inline int BeamsOn(const std::vector<Circle>& circles, size_t i, const std::vector<double>& angles,
                   double range_max_m = 12.0) {
  int beams = 0;
  for (double angle : angles) {
    double best = -1.0;
    size_t best_i = circles.size();
    for (size_t j = 0; j < circles.size(); ++j) {
      const double r = RayCircle(angle, circles[j]);
      if (r > 0.0 && (best < 0.0 || r < best)) {
        best = r;
        best_i = j;
      }
    }
    beams += (best_i == i && best <= range_max_m);
  }
  return beams;
}

inline double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double position = p * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

}  // namespace testing_support
}  // namespace slammtt
