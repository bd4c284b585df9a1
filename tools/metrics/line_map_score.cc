#include "tools/metrics/line_map_score.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tools/metrics/map_score.h"

namespace slammtt {
namespace {

// Linear interpolation between order statistics (docs/evaluation.md's percentile).
double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double at = fraction * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(at));
  const size_t above = std::min(values.size() - 1, below + 1);
  return values[below] + (at - static_cast<double>(below)) * (values[above] - values[below]);
}

// Angle between two directions modulo pi, in [0, pi / 2].
double UndirectedAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double cross = a(0) * b(1) - a(1) * b(0);
  const double angle = std::atan2(std::abs(cross), a.dot(b));  // [0, pi]
  return std::min(angle, M_PI - angle);
}

}  // namespace

LineMapScore ScoreLineMap(const std::vector<EstimatedLine>& lines,
                          const std::vector<TrueSurface>& surfaces, double max_angle_deg,
                          double max_distance_m) {
  if (!(max_angle_deg > 0.0) || !(max_distance_m > 0.0) || !std::isfinite(max_angle_deg) ||
      !std::isfinite(max_distance_m)) {
    throw std::invalid_argument("line map score: thresholds must be positive numbers");
  }
  for (const EstimatedLine& l : lines) {
    if (!l.line.allFinite() || !l.from_m.allFinite() || !l.to_m.allFinite()) {
      throw std::invalid_argument("line map score: non-finite line");
    }
  }
  for (const TrueSurface& s : surfaces) {
    if (!s.from_m.allFinite() || !s.to_m.allFinite()) {
      throw std::invalid_argument("line map score: non-finite surface");
    }
  }
  LineMapScore score;
  score.num_lines = static_cast<int>(lines.size());
  std::vector<double> angles_deg;
  std::vector<double> distances_m;
  for (const EstimatedLine& l : lines) {
    const Eigen::Vector2d n(std::cos(l.line(1)), std::sin(l.line(1)));
    const Eigen::Vector2d direction(-n(1), n(0));
    double best_cost = std::numeric_limits<double>::infinity();
    LineMatch best;
    for (const TrueSurface& s : surfaces) {
      const Eigen::Vector2d along = s.to_m - s.from_m;
      const double length = along.norm();
      if (!(length > 0.0)) continue;
      const Eigen::Vector2d u = along / length;
      const double angle = UndirectedAngle(direction, u);
      if (angle * 180.0 / M_PI > max_angle_deg) continue;
      // The landmark's stretch projected onto the segment, in [0, length] coordinates.
      const double a = (l.from_m - s.from_m).dot(u);
      const double b = (l.to_m - s.from_m).dot(u);
      const double lo = std::max(0.0, std::min(a, b));
      const double hi = std::min(length, std::max(a, b));
      if (!(hi > lo)) continue;
      const Eigen::Vector2d middle = s.from_m + 0.5 * (lo + hi) * u;
      const double distance = std::abs(middle.dot(n) - l.line(0));
      if (distance > max_distance_m) continue;
      const double cost = distance + angle;
      if (cost < best_cost) {
        best_cost = cost;
        best = {l.id, s.id, s.wall, angle * 180.0 / M_PI, distance};
      }
    }
    if (std::isfinite(best_cost)) {
      score.matches.push_back(best);
      angles_deg.push_back(best.angle_error_deg);
      distances_m.push_back(best.distance_error_m);
    } else {
      score.unmatched_ids.push_back(l.id);
    }
  }
  score.angle_error_median_deg = Percentile(angles_deg, 0.5);
  score.angle_error_p95_deg = Percentile(angles_deg, 0.95);
  score.angle_error_max_deg = Percentile(angles_deg, 1.0);
  score.distance_error_median_m = Percentile(distances_m, 0.5);
  score.distance_error_p95_m = Percentile(distances_m, 0.95);
  score.distance_error_max_m = Percentile(distances_m, 1.0);
  return score;
}

std::vector<int64_t> PointsOnWalls(const std::vector<int64_t>& ids,
                                   const std::vector<Eigen::Vector2d>& points,
                                   const std::vector<TrueSurface>& surfaces,
                                   double wall_distance_m) {
  std::vector<int64_t> on_walls;
  for (size_t k = 0; k < points.size() && k < ids.size(); ++k) {
    for (const TrueSurface& s : surfaces) {
      if (s.wall && DistanceToPath(points[k], {s.from_m, s.to_m}) <= wall_distance_m) {
        on_walls.push_back(ids[k]);
        break;
      }
    }
  }
  return on_walls;
}

}  // namespace slammtt
