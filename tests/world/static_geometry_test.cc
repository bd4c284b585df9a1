// Static objects expanded into circles and segments: a room with a door, a polyline, a rotated
// box, a chair's four legs and their ids.
#include "tools/world/static_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slammtt {
namespace {

StaticObjectSpec Room() {
  StaticObjectSpec room;
  room.id = 5;
  room.kind = ObjectKind::kWall;
  room.shape = StaticShape::kPolygon;
  room.vertices = {{0.0, 0.0}, {4.0, 0.0}, {4.0, 3.0}, {0.0, 3.0}};
  room.openings = {WallOpening{0, 1.0, 0.9}, WallOpening{2, 0.5, 1.0}};
  return room;
}

TEST(StaticGeometryTest, PolygonSidesWithOpeningsCutOut) {
  const StaticGeometry g = BuildStaticGeometry({Room()});
  EXPECT_TRUE(g.circles.empty());
  // Side 0 (0,0)-(4,0) split at 1.0-1.9; side 1 whole; side 2 (4,3)-(0,3) split at 0.5-1.5
  // from (4,3); side 3 whole.
  ASSERT_EQ(g.segments.size(), 6u);
  const Segment& a = g.segments[0].segment;
  EXPECT_DOUBLE_EQ(a.x0_m, 0.0);
  EXPECT_DOUBLE_EQ(a.x1_m, 1.0);
  const Segment& b = g.segments[1].segment;
  EXPECT_NEAR(b.x0_m, 1.9, 1e-12);
  EXPECT_DOUBLE_EQ(b.x1_m, 4.0);
  EXPECT_DOUBLE_EQ(g.segments[2].segment.y1_m, 3.0);  // side 1 whole: (4,0)-(4,3)
  EXPECT_NEAR(g.segments[3].segment.x1_m, 3.5, 1e-12);
  EXPECT_NEAR(g.segments[4].segment.x0_m, 2.5, 1e-12);
  for (const StaticSegment& s : g.segments) {
    EXPECT_EQ(s.id, 5);
    EXPECT_EQ(s.kind, ObjectKind::kWall);
    EXPECT_EQ(s.spec, 0);
  }
  // A beam through the door gets out; one beside it hits the wall.
  std::vector<Segment> walls;
  for (const StaticSegment& s : g.segments) walls.push_back(s.segment);
  EXPECT_FALSE(CastRay(1.45, 1.5, -M_PI / 2.0, {}, walls).hit());
  EXPECT_EQ(CastRay(0.5, 1.5, -M_PI / 2.0, {}, walls).segment, 0);
}

TEST(StaticGeometryTest, OpeningAtTheStartOfASideAndAPolyline) {
  StaticObjectSpec line;
  line.shape = StaticShape::kPolyline;
  line.vertices = {{0.0, 0.0}, {10.0, 0.0}, {10.0, 2.0}};
  line.openings = {WallOpening{0, 0.0, 2.0}};
  const StaticGeometry g = BuildStaticGeometry({line});
  ASSERT_EQ(g.segments.size(), 2u);  // no closing side
  EXPECT_DOUBLE_EQ(g.segments[0].segment.x0_m, 2.0);
  EXPECT_DOUBLE_EQ(g.segments[1].segment.y1_m, 2.0);
}

TEST(StaticGeometryTest, RotatedBoxHasFourClosedSides) {
  StaticObjectSpec desk;
  desk.shape = StaticShape::kBox;
  desk.kind = ObjectKind::kFurniture;
  desk.x_m = 2.0;
  desk.y_m = 1.0;
  desk.size_x_m = 1.6;
  desk.size_y_m = 0.8;
  desk.heading_rad = M_PI / 2.0;
  const StaticGeometry g = BuildStaticGeometry({desk});
  ASSERT_EQ(g.segments.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const Segment& s = g.segments[k].segment;
    const Segment& next = g.segments[(k + 1) % 4].segment;
    EXPECT_NEAR(s.x1_m, next.x0_m, 1e-12);
    EXPECT_NEAR(s.y1_m, next.y0_m, 1e-12);
    EXPECT_EQ(g.segments[k].kind, ObjectKind::kFurniture);
  }
  // Turned by 90 degrees: 0.8 wide in x, 1.6 long in y.
  std::vector<Segment> walls;
  for (const StaticSegment& s : g.segments) walls.push_back(s.segment);
  EXPECT_NEAR(CastRay(0.0, 1.0, 0.0, {}, walls).range_m, 2.0 - 0.4, 1e-12);
  EXPECT_NEAR(CastRay(2.0, -3.0, M_PI / 2.0, {}, walls).range_m, 4.0 - 0.8, 1e-12);
}

TEST(StaticGeometryTest, ChairLegsAreFourCirclesInsideTheCornersWithTheirOwnIds) {
  StaticObjectSpec chair;
  chair.id = 20;
  chair.shape = StaticShape::kLegs;
  chair.kind = ObjectKind::kFurniture;
  chair.x_m = 1.0;
  chair.y_m = 1.0;
  chair.size_x_m = 0.45;
  chair.size_y_m = 0.45;
  chair.leg_radius_m = 0.015;
  EXPECT_EQ(StaticIdCount(chair), 4);
  const StaticGeometry g = BuildStaticGeometry({chair});
  ASSERT_EQ(g.circles.size(), 4u);
  EXPECT_TRUE(g.segments.empty());
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(g.circles[k].id, 20 + static_cast<int64_t>(k));
    EXPECT_DOUBLE_EQ(g.circles[k].circle.radius_m, 0.015);
    EXPECT_NEAR(std::abs(g.circles[k].circle.x_m - 1.0), 0.225 - 0.015, 1e-12);
    EXPECT_NEAR(std::abs(g.circles[k].circle.y_m - 1.0), 0.225 - 0.015, 1e-12);
  }
  EXPECT_NEAR(g.circles[0].circle.x_m, 1.0 - 0.21, 1e-12);  // rear right first
  EXPECT_NEAR(g.circles[0].circle.y_m, 1.0 - 0.21, 1e-12);
}

TEST(StaticGeometryTest, ShapeProblemsAreFound) {
  Scenario s;
  StaticObjectSpec room = Room();
  room.openings.push_back(WallOpening{0, 1.5, 0.5});  // overlaps the first
  room.openings.push_back(WallOpening{7, 0.0, 0.5});  // no side 7
  room.openings.push_back(WallOpening{1, 2.5, 1.0});  // past the end of side 1 (3 m)
  s.statics = {room};
  const std::vector<std::string> problems = FindScenarioProblems(s);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0], "statics[0].openings[2]: overlaps opening 0");
  EXPECT_EQ(problems[1], "statics[0].openings[3]: side 7 does not exist (sides 0-3)");
  EXPECT_EQ(problems[2],
            "statics[0].openings[4]: must lie within side 1 (length 3 m) with offset >= 0 and "
            "width > 0");
  StaticObjectSpec two;
  two.shape = StaticShape::kPolygon;
  two.vertices = {{0.0, 0.0}, {1.0, 0.0}};
  s.statics = {two};
  EXPECT_EQ(FindScenarioProblems(s).at(0),
            "statics[0].vertices: a polygon needs at least 3 vertices");
}

}  // namespace
}  // namespace slammtt

namespace slammtt {
namespace {

TEST(StaticGeometryTest, HostileSizesAreRefused) {
  Scenario s;
  StaticObjectSpec wall;
  wall.shape = StaticShape::kPolyline;
  for (int i = 0; i <= 100000; ++i) wall.vertices.push_back({static_cast<double>(i), 0.0});
  s.statics = {wall};
  EXPECT_EQ(FindScenarioProblems(s).at(0), "statics[0].vertices: more than 100000 vertices");
  StaticObjectSpec post;
  s.statics.assign(100001, post);
  EXPECT_EQ(FindScenarioProblems(s).at(0), "statics: more than 100000 static objects");
}

}  // namespace
}  // namespace slammtt
