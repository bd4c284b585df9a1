// Ray casting against hand-computed geometry: distances, tangents, occlusion, max range, the
// mount offset of paper eq. 11, and the beam layout of the field of view.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/world/laser_model.h"
#include "tools/world/planar_pose.h"
#include "tools/world/ray_caster.h"

namespace slammtt {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(RayCasterTest, BeamThroughCentreHitsAtDistanceMinusRadius) {
  const BeamHit hit = CastRay(0.0, 0.0, 0.0, {Circle{5.0, 0.0, 1.0}});
  ASSERT_EQ(hit.circle, 0);
  EXPECT_DOUBLE_EQ(hit.range_m, 4.0);
}

TEST(RayCasterTest, OffCentreBeamHitsTheNearRoot) {
  // Ray along x, circle centre (5, 0.5), r = 1: (t - 5)^2 + 0.25 = 1 -> t = 5 - sqrt(0.75).
  const BeamHit hit = CastRay(0.0, 0.0, 0.0, {Circle{5.0, 0.5, 1.0}});
  ASSERT_EQ(hit.circle, 0);
  EXPECT_NEAR(hit.range_m, 5.0 - std::sqrt(0.75), 1e-12);
}

TEST(RayCasterTest, DiagonalBeamHitsAtKnownDistance) {
  // Circle centred on the 45-degree line at distance 10, radius 2: hit at 8.
  const double d = 10.0 / std::sqrt(2.0);
  const BeamHit hit = CastRay(1.0, -1.0, 45.0 * kDeg, {Circle{1.0 + d, -1.0 + d, 2.0}});
  ASSERT_EQ(hit.circle, 0);
  EXPECT_NEAR(hit.range_m, 8.0, 1e-12);
}

TEST(RayCasterTest, TangentBeamTouchesAndAPassingBeamMisses) {
  // Circle (5, 1), r = 1 touches the x axis at (5, 0).
  const BeamHit touching = CastRay(0.0, 0.0, 0.0, {Circle{5.0, 1.0, 1.0}});
  ASSERT_EQ(touching.circle, 0);
  EXPECT_NEAR(touching.range_m, 5.0, 1e-6);
  EXPECT_EQ(CastRay(0.0, 0.0, 0.0, {Circle{5.0, 1.0 + 1e-6, 1.0}}).circle, -1);
  const BeamHit grazing = CastRay(0.0, 0.0, 0.0, {Circle{5.0, 1.0 - 1e-6, 1.0}});
  ASSERT_EQ(grazing.circle, 0);
  EXPECT_NEAR(grazing.range_m, 5.0 - std::sqrt(2e-6), 1e-6);
}

TEST(RayCasterTest, NearerCircleHidesTheOneBehindWhateverTheListOrder) {
  const std::vector<Circle> circles = {Circle{10.0, 0.0, 1.0}, Circle{5.0, 0.0, 0.5}};
  const BeamHit hit = CastRay(0.0, 0.0, 0.0, circles);
  EXPECT_EQ(hit.circle, 1);
  EXPECT_DOUBLE_EQ(hit.range_m, 4.5);
  const std::vector<Circle> reversed = {circles[1], circles[0]};
  EXPECT_EQ(CastRay(0.0, 0.0, 0.0, reversed).circle, 0);
}

TEST(RayCasterTest, CircleBehindTheSensorIsNotHit) {
  EXPECT_EQ(CastRay(0.0, 0.0, 0.0, {Circle{-5.0, 0.0, 1.0}}).circle, -1);
  EXPECT_EQ(CastRay(0.0, 0.0, M_PI, {Circle{5.0, 0.0, 1.0}}).circle, -1);
}

TEST(RayCasterTest, OriginInsideACircleHitsItAtRangeZero) {
  const BeamHit hit = CastRay(0.1, 0.0, 1.0, {Circle{10.0, 0.0, 1.0}, Circle{0.0, 0.0, 0.5}});
  EXPECT_EQ(hit.circle, 1);
  EXPECT_DOUBLE_EQ(hit.range_m, 0.0);
}

TEST(RayCasterTest, ZeroRadiusCirclesAreNeverHit) {
  EXPECT_EQ(CastRay(0.0, 0.0, 0.0, {Circle{5.0, 0.0, 0.0}}).circle, -1);
}

TEST(RayCasterTest, HitsBeyondMaximumRangeGiveNoReturn) {
  const std::vector<Circle> circles = {Circle{5.0, 0.0, 1.0}};
  const Pose2D sensor{0.0, 0.0, 0.0};
  EXPECT_EQ(CastBeams(sensor, {0.0}, circles, 4.0)[0].circle, 0);
  EXPECT_EQ(CastBeams(sensor, {0.0}, circles, 3.999)[0].circle, -1);
}

TEST(RayCasterTest, MountOffsetMovesTheBeamOriginPerPaperEq11) {
  // Robot at (1, 2) facing +y; a = 0.5 forward, b = 0.2 left:
  // x_v = 1 + 0.5 cos(90) - 0.2 sin(90) = 0.8, y_v = 2 + 0.5 sin(90) + 0.2 cos(90) = 2.5.
  const Pose2D robot{1.0, 2.0, 90.0 * kDeg};
  const Pose2D sensor = SensorPoseFromRobot(robot, 0.5, 0.2);
  EXPECT_NEAR(sensor.x_m, 0.8, 1e-12);
  EXPECT_NEAR(sensor.y_m, 2.5, 1e-12);
  EXPECT_DOUBLE_EQ(sensor.heading_rad, robot.heading_rad);
  // The forward beam (sensor angle 0 = world +y) meets a circle at (0.8, 7.5), r = 1, at 4 m;
  // cast from the axle centre, 0.2 m off the circle's centre line, it would meet it at
  // 5.5 - sqrt(1 - 0.2^2): the offset matters.
  const std::vector<BeamHit> hits = CastBeams(sensor, {0.0}, {Circle{0.8, 7.5, 1.0}}, 30.0);
  ASSERT_EQ(hits[0].circle, 0);
  EXPECT_NEAR(hits[0].range_m, 4.0, 1e-12);
  const std::vector<BeamHit> from_axle = CastBeams(robot, {0.0}, {Circle{0.8, 7.5, 1.0}}, 30.0);
  ASSERT_EQ(from_axle[0].circle, 0);
  EXPECT_NEAR(from_axle[0].range_m, 5.5 - std::sqrt(1.0 - 0.04), 1e-12);
}

TEST(RayCasterTest, MountYawTurnsTheSensorHeading) {
  // The same mount turned 30 degrees CCW: same origin, heading 90 + 30 degrees; -170 degrees on
  // a robot at 90 wraps to -80.
  const Pose2D robot{1.0, 2.0, 90.0 * kDeg};
  const Pose2D sensor = SensorPoseFromRobot(robot, 0.5, 0.2, 30.0 * kDeg);
  EXPECT_NEAR(sensor.x_m, 0.8, 1e-12);
  EXPECT_NEAR(sensor.y_m, 2.5, 1e-12);
  EXPECT_NEAR(sensor.heading_rad, 120.0 * kDeg, 1e-12);
  EXPECT_NEAR(SensorPoseFromRobot(robot, 0.0, 0.0, -170.0 * kDeg).heading_rad, -80.0 * kDeg,
              1e-12);
}

TEST(RayCasterTest, SensorHeadingRotatesTheBeams) {
  // Sensor facing -x: its beam at +90 degrees points to world -y.
  const std::vector<BeamHit> hits =
      CastBeams(Pose2D{0.0, 0.0, M_PI}, {90.0 * kDeg}, {Circle{0.0, -3.0, 1.0}}, 30.0);
  ASSERT_EQ(hits[0].circle, 0);
  EXPECT_NEAR(hits[0].range_m, 2.0, 1e-12);
}

TEST(RayCasterTest, PartlyHiddenObjectKeepsOnlyItsUncoveredBeams) {
  LaserSpec laser;
  laser.fov_deg = 180.0;
  laser.resolution_deg = 0.5;
  laser.max_range_m = 30.0;
  const std::vector<double> angles = LaserBeamAngles(laser);
  // Far object (10, 0) r = 1 spans about +-5.7 degrees; a near one at (5, 0.3) r = 0.3 covers
  // its left part.
  const std::vector<Circle> alone = {Circle{10.0, 0.0, 1.0}};
  const std::vector<Circle> both = {Circle{10.0, 0.0, 1.0}, Circle{5.0, 0.3, 0.3}};
  auto count = [&](const std::vector<Circle>& circles, int which) {
    int n = 0;
    for (const BeamHit& h : CastBeams(Pose2D{}, angles, circles, 30.0)) n += h.circle == which;
    return n;
  };
  const int far_alone = count(alone, 0);
  const int far_behind = count(both, 0);
  const int near = count(both, 1);
  // asin(1/10) = 5.74 deg -> beams at -5.5 ... +5.5 every 0.5 deg: 23.
  EXPECT_EQ(far_alone, 23);
  EXPECT_GT(near, 0);
  EXPECT_GT(far_behind, 0);
  EXPECT_LT(far_behind, far_alone);
  EXPECT_LE(far_behind + near, far_alone + near);
}

TEST(RayCasterTest, SegmentBlockedByAnotherCircleOnly) {
  const std::vector<Circle> circles = {Circle{10.0, 0.0, 1.0}, Circle{5.0, 0.0, 0.5}};
  EXPECT_TRUE(SegmentBlocked(0.0, 0.0, 10.0, 0.0, circles, 0));
  EXPECT_FALSE(SegmentBlocked(0.0, 0.0, 10.0, 0.0, {circles[0]}, 0));
  // Passing 0.6 m beside the small circle: free.
  EXPECT_FALSE(SegmentBlocked(0.0, 0.6, 10.0, 0.6, {circles[1]}, -1));
  // Ending before the circle: free.
  EXPECT_FALSE(SegmentBlocked(0.0, 0.0, 4.0, 0.0, {circles[1]}, -1));
}

TEST(LaserGeometryTest, HalfCircleHasBothEdgeBeams) {
  LaserSpec laser;
  laser.fov_deg = 180.0;
  laser.resolution_deg = 1.0;
  const std::vector<double> angles = LaserBeamAngles(laser);
  ASSERT_EQ(angles.size(), 181u);
  EXPECT_NEAR(angles.front(), -M_PI / 2, 1e-12);
  EXPECT_NEAR(angles.back(), M_PI / 2, 1e-12);
  EXPECT_NEAR(angles[90], 0.0, 1e-12);
}

TEST(LaserGeometryTest, FullCircleHasNoBeamTwice) {
  LaserSpec laser;
  laser.fov_deg = 360.0;
  laser.resolution_deg = 0.9;
  const std::vector<double> angles = LaserBeamAngles(laser);
  ASSERT_EQ(angles.size(), 400u);
  EXPECT_NEAR(angles.front(), -M_PI, 1e-12);
  EXPECT_NEAR(angles.back(), M_PI - 0.9 * kDeg, 1e-12);
}

TEST(LaserGeometryTest, ObjectOutsideTheFieldOfViewGetsNoBeam) {
  LaserSpec laser;
  laser.fov_deg = 180.0;
  laser.resolution_deg = 1.0;
  laser.max_range_m = 30.0;
  const std::vector<double> angles = LaserBeamAngles(laser);
  const std::vector<Circle> behind = {Circle{-5.0, 0.0, 1.0}};
  for (const BeamHit& h : CastBeams(Pose2D{}, angles, behind, 30.0)) EXPECT_EQ(h.circle, -1);
  // The same object in front is seen.
  int seen = 0;
  for (const BeamHit& h : CastBeams(Pose2D{0.0, 0.0, M_PI}, angles, behind, 30.0)) {
    seen += h.circle == 0;
  }
  EXPECT_GT(seen, 0);
}

}  // namespace
}  // namespace slammtt

namespace slammtt {
namespace {

TEST(RayCasterSegmentTest, BeamHitsAWallHeadOnAndAtAnAngle) {
  const std::vector<Segment> wall = {Segment{4.0, -2.0, 4.0, 2.0}};
  const BeamHit ahead = CastRay(0.0, 0.0, 0.0, {}, wall);
  ASSERT_EQ(ahead.segment, 0);
  EXPECT_EQ(ahead.circle, -1);
  EXPECT_DOUBLE_EQ(ahead.range_m, 4.0);
  EXPECT_NEAR(ahead.incidence_cos, 1.0, 1e-12);
  // 20 degrees up: hits x = 4 at y = 4 tan 20, range 4 / cos 20, incidence 20 degrees.
  const double up = 20.0 * M_PI / 180.0;
  const BeamHit oblique = CastRay(0.0, 0.0, up, {}, wall);
  ASSERT_EQ(oblique.segment, 0);
  EXPECT_NEAR(oblique.range_m, 4.0 / std::cos(up), 1e-12);
  EXPECT_NEAR(oblique.incidence_cos, std::cos(up), 1e-12);
  // Past the wall's end (y = 4 tan 40 = 3.36 > 2): no hit; behind the sensor: no hit.
  EXPECT_FALSE(CastRay(0.0, 0.0, 40.0 * M_PI / 180.0, {}, wall).hit());
  EXPECT_FALSE(CastRay(0.0, 0.0, M_PI, {}, wall).hit());
  // Seen from the other side too.
  EXPECT_DOUBLE_EQ(CastRay(6.0, 0.0, M_PI, {}, wall).range_m, 2.0);
}

TEST(RayCasterSegmentTest, NearestOfCirclesAndSegmentsWins) {
  const std::vector<Circle> circles = {Circle{3.0, 0.0, 0.5}, Circle{6.0, 0.0, 0.5}};
  const std::vector<Segment> wall = {Segment{4.0, -2.0, 4.0, 2.0}};
  const BeamHit hit = CastRay(0.0, 0.0, 0.0, circles, wall);
  EXPECT_EQ(hit.circle, 0);
  EXPECT_EQ(hit.segment, -1);
  EXPECT_DOUBLE_EQ(hit.range_m, 2.5);
  // The wall hides the circle behind it.
  const BeamHit hidden = CastRay(0.0, 0.0, 0.0, {circles[1]}, wall);
  EXPECT_EQ(hidden.segment, 0);
  EXPECT_EQ(hidden.circle, -1);
  // Circle incidence: a beam through the centre meets the surface head-on; one offset by
  // r sin(60) meets it at 60 degrees.
  EXPECT_NEAR(CastRay(0.0, 0.0, 0.0, {circles[0]}).incidence_cos, 1.0, 1e-12);
  const BeamHit off = CastRay(0.0, 0.5 * std::sin(M_PI / 3.0), 0.0, {circles[0]});
  EXPECT_NEAR(off.incidence_cos, 0.5, 1e-9);
}

TEST(RayCasterSegmentTest, CastBeamsReportsSegmentsAndMaxRange) {
  const std::vector<Segment> walls = {Segment{5.0, -5.0, 5.0, 5.0}, Segment{-5.0, 5.0, 5.0, 5.0}};
  const std::vector<double> angles = {0.0, M_PI / 2.0, M_PI};
  const std::vector<BeamHit> hits = CastBeams(Pose2D{0.0, 0.0, 0.0}, angles, {}, walls, 10.0);
  EXPECT_EQ(hits[0].segment, 0);
  EXPECT_EQ(hits[1].segment, 1);
  EXPECT_FALSE(hits[2].hit());
  const std::vector<BeamHit> short_range =
      CastBeams(Pose2D{0.0, 0.0, 0.0}, angles, {}, walls, 4.0);
  EXPECT_FALSE(short_range[0].hit());
}

TEST(RayCasterSegmentTest, WallsBlockTheLineOfSight) {
  const std::vector<Segment> wall = {Segment{4.0, -2.0, 4.0, 2.0}};
  EXPECT_TRUE(SegmentBlocked(0.0, 0.0, 6.0, 0.0, {}, -1, 0, wall));
  EXPECT_FALSE(SegmentBlocked(0.0, 0.0, 3.0, 0.0, {}, -1, 0, wall));
  EXPECT_FALSE(SegmentBlocked(0.0, 3.0, 6.0, 3.0, {}, -1, 0, wall));
  EXPECT_TRUE(SegmentBlocked(0.0, 2.0, 6.0, 2.0, {}, -1, 0, wall));  // touches its end
  // Ignored circles (a person's own legs) do not block; others do.
  const std::vector<Circle> legs = {Circle{2.0, 0.1, 0.06}, Circle{2.0, -0.1, 0.06}};
  EXPECT_FALSE(SegmentBlocked(0.0, 0.0, 2.0, -0.1, legs, 0, 2, {}));
  EXPECT_TRUE(SegmentBlocked(0.0, 0.0, 2.0, -0.1, legs, 0, 1, {}));
  EXPECT_TRUE(CircleTouchesSegment(Circle{4.05, 0.0, 0.06}, wall[0]));
  EXPECT_FALSE(CircleTouchesSegment(Circle{4.07, 0.0, 0.06}, wall[0]));
}

}  // namespace
}  // namespace slammtt
