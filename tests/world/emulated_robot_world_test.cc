// The world behind the device emulators (tools/world/emulated_robot_world.h): arcs recovered
// from encoder poses, the truth following the encoders with and without slip, beams cast from
// the laser mount at the moment asked, and the truth of a scan with its beam counts.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tools/world/emulated_robot_world.h"
#include "tools/world/slipping_base.h"

namespace slammtt {
namespace {

TEST(ArcStepTest, RecoversStraightArcAndBackwardSteps) {
  const Pose2D start{1.0, 2.0, 0.3};
  for (const auto& [v, w] : std::vector<std::pair<double, double>>{
           {0.4, 0.0}, {0.4, 0.8}, {-0.3, 0.5}, {0.2, -1.5}, {0.0, 0.0}}) {
    const Pose2D end = MoveUnicycle(start, v, w, 0.7);
    const ArcStep step = ArcStepBetween(start, end);
    EXPECT_NEAR(step.distance_m, v * 0.7, 1e-12) << v << " " << w;
    EXPECT_NEAR(step.rotation_rad, w * 0.7, 1e-12) << v << " " << w;
  }
}

TEST(SlippingBaseTest, WithoutSlipTheTruthIsTheEncoderMotionFromTheStart) {
  OdometrySpec odometry;  // noise-free
  const Pose2D start{3.0, -1.0, M_PI / 2};
  const Pose2D encoder_start{10.0, 5.0, 0.0};  // the encoders' frame is their own
  SlippingBase base(start, encoder_start, odometry, 7);
  Pose2D encoders = encoder_start;
  base.Advance(0, encoders);
  for (int64_t t_us = 5000; t_us <= 4000000; t_us += 5000) {
    encoders = MoveUnicycle(encoders, 0.3, t_us <= 2000000 ? 0.0 : 0.5, 0.005);
    base.Advance(t_us, encoders);
  }
  // The same motion from `start`: 0.6 m north, then an arc of 0.6 m turning by 1 rad.
  const Pose2D expected = MoveUnicycle(MoveUnicycle(start, 0.3, 0.0, 2.0), 0.3, 0.5, 2.0);
  EXPECT_NEAR(base.pose().x_m, expected.x_m, 1e-9);
  EXPECT_NEAR(base.pose().y_m, expected.y_m, 1e-9);
  EXPECT_NEAR(base.pose().heading_rad, expected.heading_rad, 1e-9);
  EXPECT_NEAR(base.linear_mps(), 0.3, 1e-6);
  EXPECT_NEAR(base.angular_radps(), 0.5, 1e-6);
}

TEST(SlippingBaseTest, ABiasedRightWheelTurnsTheTruthRightOfTheEncoders) {
  // measured = true * (1 + bias): a right wheel that over-counts by 1 % travelled less, so a
  // straight encoder line is a slight right turn in truth: 1 % of 0.165 m per metre ... over 2 m
  // the heading turns by -2 m * 0.01 / (0.33 m) * about 1 = -0.06 rad.
  OdometrySpec odometry;
  odometry.right_slip_bias = 0.01;
  SlippingBase base(Pose2D{}, Pose2D{}, odometry, 1);
  Pose2D encoders;
  base.Advance(0, encoders);
  for (int64_t t_us = 10000; t_us <= 4000000; t_us += 10000) {
    encoders = MoveUnicycle(encoders, 0.5, 0.0, 0.01);
    base.Advance(t_us, encoders);
  }
  const double right = 1.0 / 1.01;
  const double expected_rotation = 2.0 * (right - 1.0) / 0.33;
  EXPECT_NEAR(base.pose().heading_rad, expected_rotation, 1e-6);
  EXPECT_LT(base.pose().heading_rad, -0.05);
  EXPECT_NEAR(encoders.heading_rad, 0.0, 1e-12);
}

TEST(SlippingBaseTest, SlipIsDrawnPerOdometryPeriodFromTheSeed) {
  OdometrySpec odometry;
  odometry.slip_std = 0.05;
  const auto run = [&](uint64_t seed, int64_t step_us) {
    SlippingBase base(Pose2D{}, Pose2D{}, odometry, seed);
    Pose2D encoders;
    base.Advance(0, encoders);
    for (int64_t t_us = step_us; t_us <= 3000000; t_us += step_us) {
      encoders = MoveUnicycle(encoders, 0.4, 0.2, static_cast<double>(step_us) * 1e-6);
      base.Advance(t_us, encoders);
    }
    return base.pose();
  };
  const Pose2D a = run(3, 5000);
  const Pose2D same = run(3, 5000);
  EXPECT_EQ(a.x_m, same.x_m);
  EXPECT_EQ(a.heading_rad, same.heading_rad);
  // The slip belongs to the odometry period (50 ms), not to the caller's steps: steps of 5 ms
  // and of 10 ms see the same slips (to rounding).
  const Pose2D coarser = run(3, 10000);
  EXPECT_NEAR(a.x_m, coarser.x_m, 1e-9);
  EXPECT_NEAR(a.heading_rad, coarser.heading_rad, 1e-9);
  const Pose2D other = run(4, 5000);
  EXPECT_GT(std::hypot(a.x_m - other.x_m, a.y_m - other.y_m), 1e-4);
}

// A square room 10 x 10 m around (0, 0), one post, nobody else; the robot starts at the origin
// heading east with its laser 0.2 m ahead of the axle.
Scenario Room() {
  Scenario scenario;
  scenario.name = "room";
  scenario.duration_s = 60.0;
  scenario.laser.mount_a_m = 0.2;
  scenario.laser.min_range_m = 0.15;
  scenario.laser.max_range_m = 12.0;
  StaticObjectSpec walls;
  walls.id = 1;
  walls.kind = ObjectKind::kWall;
  walls.shape = StaticShape::kPolygon;
  walls.vertices = {{-5.0, -5.0}, {5.0, -5.0}, {5.0, 5.0}, {-5.0, 5.0}};
  scenario.statics.push_back(walls);
  StaticObjectSpec post;
  post.id = 2;
  post.x_m = 0.0;
  post.y_m = 3.0;
  post.radius_m = 0.25;
  scenario.statics.push_back(post);
  return scenario;
}

TEST(EmulatedRobotWorldTest, BeamsAreCastFromTheLaserMountAtTheMomentAsked) {
  EmulatedRobotWorld world(Room(), 1);
  world.Advance(0, Pose2D{});
  // Ahead: the east wall 5 m from the axle, 4.8 m from the laser.
  ASSERT_TRUE(world.CastBeam(0.0, 0).has_value());
  EXPECT_NEAR(world.CastBeam(0.0, 0)->range_m, 4.8, 1e-9);
  // 1 s at 1 m/s east: the axle at x = 1 (the encoders' frame starts wherever they are).
  world.Advance(1000000, Pose2D{1.0, 0.0, 0.0});
  EXPECT_NEAR(world.CastBeam(0.0, 1000000)->range_m, 3.8, 1e-9);
  // Halfway between the two steps the pose is interpolated: 4.3 m.
  EXPECT_NEAR(world.CastBeam(0.0, 500000)->range_m, 4.3, 1e-9);
  // Later than the last step: the last step's world.
  EXPECT_NEAR(world.CastBeam(0.0, 2000000)->range_m, 3.8, 1e-9);
  // The post north of the laser at (1.2, 0): it stands at (0, 3), not on this beam; to the left
  // (pi/2) the north wall is 5 m away.
  EXPECT_NEAR(world.CastBeam(M_PI / 2, 1000000)->range_m, 5.0, 1e-9);
  EXPECT_DOUBLE_EQ(world.robot().pose.x_m, 1.0);
  EXPECT_DOUBLE_EQ(world.robot().sensor_pose.x_m, 1.2);
}

TEST(EmulatedRobotWorldTest, TruthOfAScanCountsItsBeamsAndStaysWithinTheHistory) {
  EmulatedRobotWorld world(Room(), 1, /*history_us=*/1000000);
  world.Advance(0, Pose2D{});
  world.Advance(500000, Pose2D{0.0, 0.0, M_PI / 2});  // turned in place to face north
  // Beams within 10 degrees either side of the sensor's x axis, one per degree.
  std::vector<double> angles;
  for (int d = -10; d <= 10; ++d) angles.push_back(d * M_PI / 180.0);
  const std::optional<TruthSnapshot> truth = world.TruthAt(500000, angles);
  ASSERT_TRUE(truth.has_value());
  EXPECT_EQ(truth->time_us, 500000);
  EXPECT_NEAR(truth->robot.pose.heading_rad, M_PI / 2, 1e-12);
  EXPECT_NEAR(truth->robot.sensor_pose.y_m, 0.2, 1e-12);
  // The post (radius 0.25 m) 2.8 m ahead of the laser spans about +-5.1 degrees: 11 beams.
  ASSERT_EQ(truth->objects.size(), 1u);
  EXPECT_EQ(truth->objects[0].id, 2);
  EXPECT_EQ(truth->objects[0].beams_on_object, 11);
  EXPECT_TRUE(truth->objects[0].visible);
  int beams_on_walls = 0;
  for (const SegmentTruth& s : truth->segments) beams_on_walls += s.beams_on_segment;
  EXPECT_EQ(beams_on_walls, 10);
  // Before the first step kept, after the last: no truth.
  world.Advance(2000000, Pose2D{0.0, 0.0, M_PI / 2});
  EXPECT_FALSE(world.TruthAt(0, angles).has_value());
  EXPECT_FALSE(world.TruthAt(2000001, angles).has_value());
  EXPECT_TRUE(world.TruthAt(1500000, angles).has_value());
}

}  // namespace
}  // namespace slammtt
