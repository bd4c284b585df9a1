// A synthetic office for the perception figures, written here (not the world library) so that
// the tests check perception against geometry of their own: a 12 x 8 m floor with two inner
// walls with doors, two desks, three chairs on thin legs and five people on two legs each, seen
// from a random place on the floor. Range noise 0.01 m + 0.5 % of the range, mixed pixels at
// depth edges with probability 0.2. Every beam remembers what it hit first.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tests/perception/synthetic_scan.h"
#include "tools/metrics/feature_score.h"

namespace slammtt {
namespace testing_support {

struct OfficeScan {
  TestScan scan;
  std::vector<TruthPerson> people;      // sensor frame
  std::vector<TruthSegment> segments;   // sensor frame
};

struct OfficeLayout {
  std::vector<WallSegment> walls;
  std::vector<WallSegment> furniture;
  std::vector<Circle> chair_legs;
};

inline void AddBox(double x0, double y0, double x1, double y1, std::vector<WallSegment>* out) {
  out->push_back({x0, y0, x1, y0});
  out->push_back({x1, y0, x1, y1});
  out->push_back({x1, y1, x0, y1});
  out->push_back({x0, y1, x0, y0});
}

// Furniture and chairs placed by the seed; walls fixed.
inline OfficeLayout MakeOfficeLayout(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  OfficeLayout layout;
  layout.walls = {{0, 0, 12, 0}, {12, 0, 12, 8}, {12, 8, 0, 8}, {0, 8, 0, 0},
                  {6, 0, 6, 3},  {6, 4, 6, 8},   {6, 5, 8.5, 5}, {9.5, 5, 12, 5}};
  const double dx = 1.0 + 2.0 * u(rng);
  AddBox(dx, 6.2, dx + 1.4, 6.9, &layout.furniture);
  const double ex = 7.0 + 2.5 * u(rng);
  AddBox(ex, 0.8, ex + 1.4, 1.5, &layout.furniture);
  for (int c = 0; c < 3; ++c) {
    const double cx = c == 0 ? dx + 0.5 : (c == 1 ? ex + 0.5 : 3.0 + 2.0 * u(rng));
    const double cy = c == 0 ? 5.4 : (c == 1 ? 1.9 : 1.0 + 1.0 * u(rng));
    const double r = 0.015 + 0.01 * u(rng);
    for (double ox : {0.0, 0.45}) {
      for (double oy : {0.0, 0.45}) layout.chair_legs.push_back({cx + ox, cy + oy, r});
    }
  }
  return layout;
}

inline double DistanceToWallSegment(double x, double y, const WallSegment& w) {
  const double ex = w.x1_m - w.x0_m, ey = w.y1_m - w.y0_m;
  const double t = std::clamp(((x - w.x0_m) * ex + (y - w.y0_m) * ey) / (ex * ex + ey * ey), 0.0,
                              1.0);
  return std::hypot(x - (w.x0_m + t * ex), y - (w.y0_m + t * ey));
}

inline bool Clear(double x, double y, double margin, const OfficeLayout& layout) {
  if (x < margin || x > 12 - margin || y < margin || y > 8 - margin) return false;
  for (const auto* list : {&layout.walls, &layout.furniture}) {
    for (const WallSegment& w : *list) {
      if (DistanceToWallSegment(x, y, w) < margin) return false;
    }
  }
  for (const Circle& c : layout.chair_legs) {
    if (std::hypot(x - c.x_m, y - c.y_m) < margin + 0.3) return false;
  }
  return true;
}

// One scan: five people and the sensor at random clear places (people at least 0.7 m apart);
// spacing_deg over 360 degrees, 12 m range (beams beyond: no return).
inline OfficeScan MakeOfficeScan(const OfficeLayout& layout, double spacing_deg,
                                 std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sx = 0, sy = 0;
  do {
    sx = 12.0 * u(*rng);
    sy = 8.0 * u(*rng);
  } while (!Clear(sx, sy, 0.5, layout));
  std::vector<Circle> circles;  // legs first (2 per person), then chair legs
  std::vector<Eigen::Vector2d> centres;
  while (centres.size() < 5) {
    const double px = 12.0 * u(*rng), py = 8.0 * u(*rng);
    if (!Clear(px, py, 0.45, layout) || std::hypot(px - sx, py - sy) < 0.8) continue;
    bool apart = true;
    for (const Eigen::Vector2d& c : centres) {
      apart = apart && (c - Eigen::Vector2d(px, py)).norm() > 0.7;
    }
    if (!apart) continue;
    centres.emplace_back(px, py);
    const double heading = 2.0 * M_PI * u(*rng);
    const double stride = 0.6 * (u(*rng) - 0.5);  // along the heading, -0.3..0.3 m
    const double ax = std::cos(heading), ay = std::sin(heading);
    for (double side : {1.0, -1.0}) {
      const double along = side * 0.5 * stride;
      const double across = side * 0.1;
      circles.push_back({px + along * ax - across * ay, py + along * ay + across * ax,
                         0.05 + 0.02 * u(*rng)});
    }
  }
  for (const Circle& c : layout.chair_legs) circles.push_back(c);
  std::vector<WallSegment> surfaces = layout.walls;
  surfaces.insert(surfaces.end(), layout.furniture.begin(), layout.furniture.end());
  // Into the sensor frame (heading 0: a translation).
  for (Circle& c : circles) {
    c.x_m -= sx;
    c.y_m -= sy;
  }
  for (WallSegment& w : surfaces) {
    w.x0_m -= sx;
    w.x1_m -= sx;
    w.y0_m -= sy;
    w.y1_m -= sy;
  }
  const int n = static_cast<int>(std::lround(360.0 / spacing_deg));
  const std::vector<double> angles = EvenAngles(-M_PI, 2.0 * M_PI, n, true);
  OfficeScan out;
  std::vector<int> leg_beams(circles.size(), 0);
  std::vector<double> truth(angles.size());
  for (size_t i = 0; i < angles.size(); ++i) {
    double best = -1.0;
    int hit = -1;
    for (size_t j = 0; j < circles.size(); ++j) {
      const double r = RayCircle(angles[i], circles[j]);
      if (r > 0.0 && (best < 0.0 || r < best)) {
        best = r;
        hit = static_cast<int>(j);
      }
    }
    for (const WallSegment& w : surfaces) {
      const double r = RaySegment(angles[i], w);
      if (r > 0.0 && (best < 0.0 || r < best)) {
        best = r;
        hit = -1;
      }
    }
    truth[i] = best;
    if (hit >= 0 && best <= 12.0) ++leg_beams[static_cast<size_t>(hit)];
  }
  std::normal_distribution<double> noise(0.0, 1.0);
  for (size_t i = 0; i < angles.size(); ++i) {
    double r = truth[i];
    const double neighbour = truth[i > 0 ? i - 1 : angles.size() - 1];
    if (r > 0.0 && neighbour > 0.0 && std::abs(neighbour - r) > 0.3 && u(*rng) < 0.2) {
      r = std::min(r, neighbour) + u(*rng) * std::abs(neighbour - r);
    }
    if (r > 0.0) r += (0.01 + 0.005 * r) * noise(*rng);
    const bool hit = r > 0.0 && r <= 12.0;
    out.scan.angle_rad.push_back(static_cast<float>(angles[i]));
    out.scan.range_m.push_back(hit ? static_cast<float>(r) : 0.0f);
    out.scan.valid.push_back(hit ? 1 : 0);
  }
  out.scan.range_max_m = 12.0;
  for (size_t p = 0; p < centres.size(); ++p) {
    TruthPerson person;
    person.centre_m = centres[p] - Eigen::Vector2d(sx, sy);
    person.max_leg_beams = std::max(leg_beams[2 * p], leg_beams[2 * p + 1]);
    out.people.push_back(person);
  }
  for (size_t k = 0; k < surfaces.size(); ++k) {
    TruthSegment s;
    s.first_m = Eigen::Vector2d(surfaces[k].x0_m, surfaces[k].y0_m);
    s.second_m = Eigen::Vector2d(surfaces[k].x1_m, surfaces[k].y1_m);
    s.wall = k < layout.walls.size();
    out.segments.push_back(s);
  }
  return out;
}

}  // namespace testing_support
}  // namespace slammtt
