// The line landmarks' score (tools/metrics/line_map_score.h): matches, errors, surfaces that a
// line does not overlap, points on walls, bad input.
#include "tools/metrics/line_map_score.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace slammtt {
namespace {

// A line through `from` and `to` as (rho, alpha), its stretch between them.
EstimatedLine Through(int64_t id, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  const Eigen::Vector2d d = (to - from).normalized();
  const Eigen::Vector2d n(d(1), -d(0));
  return {id, Eigen::Vector2d(from.dot(n), std::atan2(n(1), n(0))), from, to};
}

TEST(LineMapScoreTest, AngleAndDistanceErrorsOfTheBestSurface) {
  // A wall along y = 0 from x = 0 to 4 and a desk side along x = 2 from y = 1 to 2.
  const std::vector<TrueSurface> surfaces = {{1, true, {0.0, 0.0}, {4.0, 0.0}},
                                             {2, false, {2.0, 1.0}, {2.0, 2.0}}};
  // Line 10: the wall 0.05 m off and turned by 1 degree about its middle (x = 2).
  const double tilt = 1.0 * M_PI / 180.0;
  const Eigen::Vector2d centre(2.0, 0.05);
  const Eigen::Vector2d half(1.5 * std::cos(tilt), 1.5 * std::sin(tilt));
  // Line 11: the desk side, exact, over part of it. Line 12: nowhere near a surface.
  const std::vector<EstimatedLine> lines = {Through(10, centre - half, centre + half),
                                            Through(11, {2.0, 1.2}, {2.0, 1.8}),
                                            Through(12, {10.0, 10.0}, {11.0, 10.0})};
  const LineMapScore score = ScoreLineMap(lines, surfaces, 10.0, 0.5);
  EXPECT_EQ(score.num_lines, 3);
  ASSERT_EQ(score.matches.size(), 2u);
  EXPECT_EQ(score.matches[0].line_id, 10);
  EXPECT_EQ(score.matches[0].surface_id, 1);
  EXPECT_TRUE(score.matches[0].wall);
  EXPECT_NEAR(score.matches[0].angle_error_deg, 1.0, 1e-9);
  // The overlap's midpoint on the wall is (2, 0) (the stretch covers x = 0.5-3.5).
  EXPECT_NEAR(score.matches[0].distance_error_m, 0.05 * std::cos(tilt), 1e-9);
  EXPECT_EQ(score.matches[1].surface_id, 2);
  EXPECT_FALSE(score.matches[1].wall);
  EXPECT_NEAR(score.matches[1].angle_error_deg, 0.0, 1e-9);
  EXPECT_NEAR(score.matches[1].distance_error_m, 0.0, 1e-9);
  EXPECT_EQ(score.unmatched_ids, std::vector<int64_t>{12});
  EXPECT_NEAR(score.angle_error_max_deg, 1.0, 1e-9);
  EXPECT_NEAR(score.angle_error_median_deg, 0.5, 1e-9);
}

TEST(LineMapScoreTest, ACollinearLineBesideTheSegmentDoesNotMatchIt) {
  const std::vector<TrueSurface> surfaces = {{1, true, {0.0, 0.0}, {4.0, 0.0}}};
  const LineMapScore score =
      ScoreLineMap({Through(5, {5.0, 0.0}, {6.0, 0.0})}, surfaces, 10.0, 0.5);
  EXPECT_TRUE(score.matches.empty());
  EXPECT_EQ(score.unmatched_ids, std::vector<int64_t>{5});
}

TEST(LineMapScoreTest, PointsOnWallsAreThoseNearAWallNotAFurnitureSide) {
  const std::vector<TrueSurface> surfaces = {{1, true, {0.0, 0.0}, {4.0, 0.0}},
                                             {2, false, {2.0, 1.0}, {2.0, 2.0}}};
  const std::vector<int64_t> on = PointsOnWalls(
      {1, 2, 3, 4}, {{1.0, 0.1}, {2.0, 1.5}, {5.0, 0.0}, {3.0, -0.19}}, surfaces, 0.2);
  EXPECT_EQ(on, (std::vector<int64_t>{1, 4}));
}

TEST(LineMapScoreTest, BadInputThrows) {
  const std::vector<TrueSurface> surfaces = {{1, true, {0.0, 0.0}, {4.0, 0.0}}};
  EXPECT_THROW(ScoreLineMap({}, surfaces, 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(ScoreLineMap({}, surfaces, 10.0, -1.0), std::invalid_argument);
  EstimatedLine bad = Through(1, {0.0, 0.0}, {1.0, 0.0});
  bad.from_m(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ScoreLineMap({bad}, surfaces, 10.0, 0.5), std::invalid_argument);
  EXPECT_NO_THROW(ScoreLineMap({}, {}, 10.0, 0.5));
}

}  // namespace
}  // namespace slammtt
