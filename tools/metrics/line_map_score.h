// Score of the estimator's line landmarks (walls and furniture sides, MAP's lines) against the
// true straight static surfaces (GROUND_TRUTH's segments), and the count of point landmarks that
// lie on a wall. Definitions in docs/evaluation.md, "Line landmarks":
//
// - a line landmark is the infinite line (rho, alpha) (x cos alpha + y sin alpha = rho) with
//   the stretch of it the estimator saw (from_m, to_m), in the truth frame;
// - it matches the true segment of least cost among those that it overlaps (its stretch
//   projected onto the segment's line shares some length with the segment), that lie within
//   `max_angle_deg` of its direction and whose midpoint of the overlap lies within
//   `max_distance_m` of its line; cost = distance [m] + angle [rad] x 1 m. Several landmarks
//   may match one segment (a wall seen as two pieces);
// - angle error: the angle between the landmark's and the segment's directions (modulo 180
//   degrees); distance error: the distance from the midpoint of the overlap, on the segment, to
//   the landmark's line;
// - a point on a wall: within `wall_distance_m` of a segment of kind wall (PointsOnWalls).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace slammtt {

struct EstimatedLine {
  int64_t id = 0;
  Eigen::Vector2d line = Eigen::Vector2d::Zero();  // (rho_m, alpha_rad)
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
};

struct TrueSurface {
  int64_t id = 0;
  bool wall = true;  // false: a furniture side
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
};

struct LineMatch {
  int64_t line_id = 0;
  int64_t surface_id = 0;
  bool wall = true;
  double angle_error_deg = 0.0;
  double distance_error_m = 0.0;
};

struct LineMapScore {
  int num_lines = 0;
  std::vector<LineMatch> matches;       // one per matched line, in the order of the lines
  std::vector<int64_t> unmatched_ids;   // lines matching no true surface
  // Over the matches (0 without any): median, 95th percentile (linear between order
  // statistics) and maximum.
  double angle_error_median_deg = 0.0;
  double angle_error_p95_deg = 0.0;
  double angle_error_max_deg = 0.0;
  double distance_error_median_m = 0.0;
  double distance_error_p95_m = 0.0;
  double distance_error_max_m = 0.0;
};

// std::invalid_argument on non-finite input or thresholds that are not positive.
LineMapScore ScoreLineMap(const std::vector<EstimatedLine>& lines,
                          const std::vector<TrueSurface>& surfaces, double max_angle_deg,
                          double max_distance_m);

// The ids of the points within `wall_distance_m` of a true surface of kind wall.
std::vector<int64_t> PointsOnWalls(const std::vector<int64_t>& ids,
                                   const std::vector<Eigen::Vector2d>& points,
                                   const std::vector<TrueSurface>& surfaces,
                                   double wall_distance_m);

}  // namespace slammtt
