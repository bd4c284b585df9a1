#include "tools/metrics/map_score.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace slammtt {
namespace {

IdentifiedPoint At(int64_t id, double x, double y) {
  return IdentifiedPoint{id, Eigen::Vector2d(x, y)};
}

TEST(MapScoreTest, HandComputedMatchRecallAndMovers) {
  const std::vector<IdentifiedPoint> statics = {At(1, 0, 0), At(2, 10, 0), At(3, 20, 0)};
  const std::vector<IdentifiedPoint> landmarks = {
      At(100, 0.3, 0), At(101, 10, 0.4),  // two good landmarks
      At(102, 5, 5.5),                    // 0.5 m beside the middle of a mover's path
      At(103, 40, 40)};                   // nothing there
  // One mover walked from (0, 5) to (10, 5): the landmark is far from both path points but near
  // the segment between them.
  const std::vector<std::vector<Eigen::Vector2d>> paths = {
      {Eigen::Vector2d(0, 5), Eigen::Vector2d(10, 5)}};
  const MapScore s = ScoreMap(landmarks, statics, paths, 1.0);
  EXPECT_EQ(s.num_landmarks, 4);
  EXPECT_EQ(s.num_static_truth, 3);
  EXPECT_EQ(s.num_matched, 2);
  EXPECT_DOUBLE_EQ(*s.static_recall, 2.0 / 3.0);
  EXPECT_NEAR(*s.landmark_rmse_m, std::sqrt((0.09 + 0.16) / 2.0), 1e-12);
  EXPECT_NEAR(s.landmark_max_error_m, 0.4, 1e-12);
  EXPECT_EQ(s.num_movers_in_static_map, 1);
  EXPECT_EQ(s.mover_landmarks, std::vector<int64_t>{102});
  EXPECT_EQ(s.unexplained_landmarks, std::vector<int64_t>{103});
}

TEST(MapScoreTest, ALandmarkOnAStaticObjectIsNotAMoverEvenNearAPath) {
  const MapScore s = ScoreMap({At(1, 0, 0.2)}, {At(9, 0, 0)},
                              {{Eigen::Vector2d(-5, 0), Eigen::Vector2d(5, 0)}}, 1.0);
  EXPECT_EQ(s.num_matched, 1);
  EXPECT_EQ(s.num_movers_in_static_map, 0);
}

TEST(MapScoreTest, EmptyMapAndNoStaticObjects) {
  const MapScore empty_map = ScoreMap({}, {At(1, 0, 0)}, {}, 1.0);
  EXPECT_DOUBLE_EQ(*empty_map.static_recall, 0.0);
  EXPECT_FALSE(empty_map.landmark_rmse_m.has_value());
  const MapScore no_statics = ScoreMap({At(1, 0, 0)}, {}, {{Eigen::Vector2d(0.5, 0)}}, 1.0);
  EXPECT_FALSE(no_statics.static_recall.has_value());
  EXPECT_EQ(no_statics.num_movers_in_static_map, 1);  // a one-point path counts too
}

TEST(MapScoreTest, DistanceToPath) {
  const std::vector<Eigen::Vector2d> path = {Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0),
                                             Eigen::Vector2d(4, 4)};
  EXPECT_DOUBLE_EQ(DistanceToPath(Eigen::Vector2d(2, 1), path), 1.0);
  EXPECT_DOUBLE_EQ(DistanceToPath(Eigen::Vector2d(5, 2), path), 1.0);
  EXPECT_DOUBLE_EQ(DistanceToPath(Eigen::Vector2d(-3, 4), path), 5.0);
  EXPECT_TRUE(std::isinf(DistanceToPath(Eigen::Vector2d(0, 0), {})));
}

TEST(MapScoreTest, RejectsBadInput) {
  EXPECT_THROW(ScoreMap({}, {}, {}, -1.0), std::invalid_argument);
  EXPECT_THROW(ScoreMap({At(1, NAN, 0)}, {}, {}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
