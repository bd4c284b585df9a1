// The simulator as a whole: event times and order, robot truth, odometry against truth,
// movers entering and leaving, output modes sharing their random streams, beam counts.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

Scenario SmallScenario() {
  Scenario s;
  s.duration_s = 2.0;
  s.laser.fov_deg = 180.0;
  s.laser.resolution_deg = 1.0;
  s.laser.max_range_m = 30.0;
  s.laser.rate_hz = 8.0;
  s.odometry.rate_hz = 20.0;
  s.robot.profile = {VelocitySegment{10.0, 1.0, 0.0}};
  StaticObjectSpec post;
  post.id = 1;
  post.x_m = 6.0;
  post.y_m = 2.0;
  post.radius_m = 0.3;
  s.statics = {post};
  MoverSpec m;
  m.id = 101;
  m.kind = MoverKind::kConstantVelocity;
  m.start_x_m = 8.0;
  m.start_y_m = -3.0;
  m.vy_mps = 0.75;
  s.movers = {m};
  return s;
}

std::vector<WorldEvent> RunAll(const Scenario& s, uint64_t seed, SensorOutput output) {
  WorldSimulator world(s, seed, output);
  std::vector<WorldEvent> events;
  while (!world.Done()) events.push_back(world.Next());
  return events;
}

TEST(WorldSimulatorTest, EventTimesRatesAndOrder) {
  const std::vector<WorldEvent> events = RunAll(SmallScenario(), 1, SensorOutput::kScans);
  int odometry = 0;
  int scans = 0;
  int64_t last = -1;
  for (size_t i = 0; i < events.size(); ++i) {
    const WorldEvent& e = events[i];
    EXPECT_GE(e.time_us, last);
    if (e.time_us == last) {
      // Equal times: odometry before the sensor frame.
      EXPECT_EQ(events[i - 1].kind, WorldEvent::Kind::kOdometry);
      EXPECT_EQ(e.kind, WorldEvent::Kind::kSensor);
    }
    last = e.time_us;
    if (e.kind == WorldEvent::Kind::kOdometry) {
      EXPECT_EQ(e.time_us, odometry * 50000);
      EXPECT_EQ(e.odometry.sequence, odometry);
      ++odometry;
    } else {
      EXPECT_EQ(e.time_us, scans * 125000);
      EXPECT_EQ(e.sensor.sequence, scans);
      EXPECT_EQ(e.sensor.truth.time_us, e.time_us);
      ++scans;
    }
  }
  EXPECT_EQ(odometry, 41);  // 0 ... 2 s at 20 Hz, both ends included
  EXPECT_EQ(scans, 17);     // 0 ... 2 s at 8 Hz
  EXPECT_EQ(last, 2000000);
}

TEST(WorldSimulatorTest, NextAfterTheEndIsAnError) {
  Scenario s = SmallScenario();
  s.duration_s = 0.1;
  WorldSimulator world(s, 1, SensorOutput::kScans);
  while (!world.Done()) world.Next();
  EXPECT_THROW(world.Next(), std::logic_error);
}

TEST(WorldSimulatorTest, InvalidScenarioIsRefusedWithEveryProblem) {
  Scenario s = SmallScenario();
  s.statics[0].radius_m = -1.0;
  s.robot.profile[0].linear_mps = 2.5;
  try {
    WorldSimulator world(s, 1, SensorOutput::kScans);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("statics[0].radius_m: must be positive, got -1"), std::string::npos)
        << what;
    EXPECT_NE(what.find("robot.profile[0].linear_mps"), std::string::npos) << what;
  }
}

TEST(WorldSimulatorTest, RobotTruthFollowsTheProfileAndTheSensorMount) {
  Scenario s = SmallScenario();
  s.robot.start = Pose2D{1.0, 2.0, M_PI / 2};
  s.robot.profile = {VelocitySegment{1.0, 1.0, 0.0}, VelocitySegment{1.0, 0.0, M_PI / 2}};
  s.laser.mount_a_m = 0.2;
  for (const WorldEvent& e : RunAll(s, 1, SensorOutput::kScans)) {
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const double t = static_cast<double>(e.time_us) * 1e-6;
    const RobotTruth& r = e.sensor.truth.robot;
    if (t <= 1.0) {
      EXPECT_NEAR(r.pose.x_m, 1.0, 1e-9);
      EXPECT_NEAR(r.pose.y_m, 2.0 + t, 1e-9);
      EXPECT_NEAR(r.pose.heading_rad, M_PI / 2, 1e-9);
    } else {
      EXPECT_NEAR(r.pose.y_m, 3.0, 1e-9);
      EXPECT_NEAR(r.pose.heading_rad, WrapAngle(M_PI / 2 + (t - 1.0) * M_PI / 2), 1e-9);
      // At t = 2 s the profile has ended: the robot stands.
      EXPECT_DOUBLE_EQ(r.angular_radps, t < 2.0 ? M_PI / 2 : 0.0);
    }
    EXPECT_NEAR(r.sensor_pose.x_m, r.pose.x_m + 0.2 * std::cos(r.pose.heading_rad), 1e-12);
    EXPECT_NEAR(r.sensor_pose.y_m, r.pose.y_m + 0.2 * std::sin(r.pose.heading_rad), 1e-12);
    EXPECT_DOUBLE_EQ(r.sensor_pose.heading_rad, r.pose.heading_rad);
  }
  s.laser.mount_yaw_deg = -45.0;  // a laser turned to the right
  for (const WorldEvent& e : RunAll(s, 1, SensorOutput::kScans)) {
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const RobotTruth& r = e.sensor.truth.robot;
    EXPECT_NEAR(WrapAngle(r.sensor_pose.heading_rad - r.pose.heading_rad), -M_PI / 4, 1e-12);
    EXPECT_NEAR(r.sensor_pose.x_m, r.pose.x_m + 0.2 * std::cos(r.pose.heading_rad), 1e-12);
  }
}

TEST(WorldSimulatorTest, NoiseFreeOdometryOfStraightLineAndTurnInPlaceMatchesTruthExactly) {
  Scenario s = SmallScenario();
  s.duration_s = 6.0;
  s.robot.profile = {VelocitySegment{2.0, 1.5, 0.0}, VelocitySegment{2.0, 0.0, 0.8},
                     VelocitySegment{2.0, -0.5, 0.0}};
  WorldSimulator world(s, 1, SensorOutput::kScans);
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kOdometry) continue;
    // Robot starts at the world origin with heading 0: odometry frame = world frame.
    EXPECT_NEAR(e.odometry.pose.x_m, world.robot().pose.x_m, 1e-9) << e.time_us;
    EXPECT_NEAR(e.odometry.pose.y_m, world.robot().pose.y_m, 1e-9) << e.time_us;
    EXPECT_NEAR(WrapAngle(e.odometry.pose.heading_rad - world.robot().pose.heading_rad), 0.0, 1e-9);
  }
  EXPECT_NEAR(world.robot().pose.heading_rad, 1.6, 1e-9);
  EXPECT_NEAR(world.robot().pose.x_m, 3.0 - std::cos(1.6), 1e-9);
}

TEST(WorldSimulatorTest, OdometryStartsAtZeroInItsOwnFrame) {
  Scenario s = SmallScenario();
  s.robot.start = Pose2D{10.0, -4.0, 1.0};
  const std::vector<WorldEvent> events = RunAll(s, 1, SensorOutput::kScans);
  ASSERT_EQ(events[0].kind, WorldEvent::Kind::kOdometry);
  EXPECT_EQ(events[0].odometry.pose.x_m, 0.0);
  EXPECT_EQ(events[0].odometry.pose.heading_rad, 0.0);
  // After 2 s at 1 m/s the odometry says 2 m straight ahead in its own frame.
  const OdometryReading& last = events[events.size() - 2].kind == WorldEvent::Kind::kOdometry
                                    ? events[events.size() - 2].odometry
                                    : events.back().odometry;
  EXPECT_NEAR(last.pose.x_m, 2.0, 1e-9);
  EXPECT_NEAR(last.pose.y_m, 0.0, 1e-9);
}

TEST(WorldSimulatorTest, MoversAppearAndDisappearInTheTruth) {
  Scenario s = SmallScenario();
  s.movers[0].appear_s = 0.5;
  s.movers[0].disappear_s = 1.5;
  for (const WorldEvent& e : RunAll(s, 1, SensorOutput::kScans)) {
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const double t = static_cast<double>(e.time_us) * 1e-6;
    const bool present = t >= 0.5 && t < 1.5;
    ASSERT_EQ(e.sensor.truth.objects.size(), present ? 2u : 1u) << t;
    EXPECT_TRUE(e.sensor.truth.objects[0].is_static);
    if (present) {
      const ObjectTruth& m = e.sensor.truth.objects[1];
      EXPECT_EQ(m.id, 101);
      EXPECT_FALSE(m.is_static);
      EXPECT_NEAR(m.y_m, -3.0 + 0.75 * (t - 0.5), 1e-9);
      EXPECT_DOUBLE_EQ(m.vy_mps, 0.75);
    }
    for (const SimulatedBeam& b : e.sensor.scan) {
      EXPECT_LT(b.object, static_cast<int>(e.sensor.truth.objects.size()));
    }
  }
}

TEST(WorldSimulatorTest, BeamCountsAndVisibilityMatchTheScan) {
  for (const WorldEvent& e : RunAll(SmallScenario(), 3, SensorOutput::kScans)) {
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    ASSERT_TRUE(e.sensor.has_scan);
    EXPECT_FALSE(e.sensor.has_features);
    EXPECT_EQ(e.sensor.scan.size(), 181u);
    std::vector<int> counts(e.sensor.truth.objects.size(), 0);
    for (const SimulatedBeam& b : e.sensor.scan) {
      if (b.valid) ++counts[static_cast<size_t>(b.object)];
    }
    for (size_t i = 0; i < counts.size(); ++i) {
      EXPECT_EQ(e.sensor.truth.objects[i].beams_on_object, counts[i]);
      EXPECT_EQ(e.sensor.truth.objects[i].visible, counts[i] >= 1);
    }
    EXPECT_GT(counts[0], 0);  // the landmark ahead is always in view
  }
}

TEST(WorldSimulatorTest, OutputModesShareTheirRandomStreams) {
  const Scenario s = SmallScenario();
  Scenario noisy = s;
  noisy.odometry.encoder_noise_rad = 0.01;
  noisy.laser.range_noise_m = 0.02;
  const std::vector<WorldEvent> scans = RunAll(noisy, 9, SensorOutput::kScans);
  const std::vector<WorldEvent> features = RunAll(noisy, 9, SensorOutput::kFeatures);
  const std::vector<WorldEvent> both = RunAll(noisy, 9, SensorOutput::kBoth);
  ASSERT_EQ(scans.size(), both.size());
  ASSERT_EQ(features.size(), both.size());
  for (size_t i = 0; i < both.size(); ++i) {
    if (both[i].kind == WorldEvent::Kind::kOdometry) {
      EXPECT_EQ(both[i].odometry.pose.x_m, scans[i].odometry.pose.x_m);
      EXPECT_EQ(both[i].odometry.pose.x_m, features[i].odometry.pose.x_m);
      continue;
    }
    ASSERT_EQ(both[i].sensor.scan.size(), scans[i].sensor.scan.size());
    for (size_t b = 0; b < both[i].sensor.scan.size(); ++b) {
      EXPECT_EQ(both[i].sensor.scan[b].range_m, scans[i].sensor.scan[b].range_m);
    }
    ASSERT_EQ(both[i].sensor.features.size(), features[i].sensor.features.size());
    for (size_t f = 0; f < both[i].sensor.features.size(); ++f) {
      EXPECT_EQ(both[i].sensor.features[f].range_m, features[i].sensor.features[f].range_m);
    }
    EXPECT_FALSE(features[i].sensor.has_scan);
    EXPECT_TRUE(features[i].sensor.has_features);
  }
}

TEST(WorldSimulatorTest, SameSeedSameEventsOtherSeedOtherNoise) {
  Scenario s = SmallScenario();
  s.laser.range_noise_m = 0.02;
  const std::vector<WorldEvent> a = RunAll(s, 4, SensorOutput::kScans);
  const std::vector<WorldEvent> b = RunAll(s, 4, SensorOutput::kScans);
  const std::vector<WorldEvent> c = RunAll(s, 5, SensorOutput::kScans);
  bool any_difference = false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].kind != WorldEvent::Kind::kSensor) continue;
    for (size_t k = 0; k < a[i].sensor.scan.size(); ++k) {
      EXPECT_EQ(a[i].sensor.scan[k].range_m, b[i].sensor.scan[k].range_m);
      any_difference = any_difference || a[i].sensor.scan[k].range_m != c[i].sensor.scan[k].range_m;
    }
  }
  EXPECT_TRUE(any_difference);
}

TEST(WorldSimulatorTest, WaypointRobotVisitsEveryWaypointAndStops) {
  Scenario s = SmallScenario();
  s.duration_s = 60.0;
  s.robot.profile.clear();
  s.robot.waypoints = {PlanarPoint{5.0, 0.0}, PlanarPoint{5.0, 5.0}, PlanarPoint{0.0, 5.0}};
  s.robot.speed_mps = 1.0;
  s.robot.max_angular_radps = 1.0;
  WorldSimulator world(s, 1, SensorOutput::kScans);
  std::vector<double> closest(3, 1e9);
  double fastest = 0.0;
  while (!world.Done()) {
    world.Next();
    for (size_t i = 0; i < 3; ++i) {
      const Pose2D& pose = world.robot().pose;
      closest[i] = std::min(closest[i], std::hypot(pose.x_m - s.robot.waypoints[i].x_m,
                                                   pose.y_m - s.robot.waypoints[i].y_m));
    }
    fastest = std::max(fastest, std::abs(world.robot().linear_mps));
  }
  for (double d : closest) EXPECT_LE(d, s.robot.waypoint_tolerance_m + 0.02);
  EXPECT_LE(fastest, 1.0);
  EXPECT_EQ(world.robot().linear_mps, 0.0);  // stopped after the last waypoint
  EXPECT_EQ(world.robot().angular_radps, 0.0);
}

TEST(WorldSimulatorTest, CommandOverrideDrivesTheRobotAndIsClamped) {
  Scenario s = SmallScenario();
  WorldSimulator world(s, 1, SensorOutput::kScans);
  world.SetCommandOverride(VelocityCommand{5.0, 0.0});
  while (!world.Done()) world.Next();
  EXPECT_NEAR(world.robot().pose.x_m, 2.0 * kMaxRobotSpeedMps, 1e-9);
}

// A 6 x 4 m room with a door in its bottom side, a chair and a legged person walking inside it.
Scenario RoomWithAPerson() {
  Scenario s;
  s.duration_s = 4.0;
  s.laser.range_noise_m = 0.0;
  s.robot.start = Pose2D{1.0, 2.0, 0.0};
  StaticObjectSpec room;
  room.id = 1;
  room.kind = ObjectKind::kWall;
  room.shape = StaticShape::kPolygon;
  room.vertices = {{0.0, 0.0}, {6.0, 0.0}, {6.0, 4.0}, {0.0, 4.0}};
  room.openings = {WallOpening{0, 2.0, 1.0}};
  StaticObjectSpec chair;
  chair.id = 2;
  chair.kind = ObjectKind::kFurniture;
  chair.shape = StaticShape::kLegs;
  chair.x_m = 2.0;
  chair.y_m = 3.0;
  chair.size_x_m = 0.45;
  chair.size_y_m = 0.45;
  chair.leg_radius_m = 0.02;
  s.statics = {room, chair};
  MoverSpec person;
  person.id = 100;
  person.kind = MoverKind::kConstantVelocity;
  person.start_x_m = 3.0;
  person.start_y_m = 1.0;
  person.vx_mps = 0.5;
  person.body = MoverBody::kLegs;
  s.movers = {person};
  return s;
}

TEST(WorldSimulatorTest, WallsFurnitureAndLegsInTheTruthAndTheScan) {
  WorldSimulator world(RoomWithAPerson(), 1, SensorOutput::kBoth);
  int frames = 0;
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    ++frames;
    const TruthSnapshot& truth = e.sensor.truth;
    // 4 chair legs, then the person and its two legs.
    ASSERT_EQ(truth.objects.size(), 7u);
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(truth.objects[static_cast<size_t>(k)].kind, ObjectKind::kFurniture);
      EXPECT_EQ(truth.objects[static_cast<size_t>(k)].id, 2 + k);
    }
    const ObjectTruth& person = truth.objects[4];
    EXPECT_EQ(person.kind, ObjectKind::kPerson);
    EXPECT_EQ(person.vx_mps, 0.5);
    for (size_t k = 5; k < 7; ++k) {
      EXPECT_EQ(truth.objects[k].kind, ObjectKind::kLeg);
      EXPECT_EQ(truth.objects[k].parent_id, 100);
      EXPECT_EQ(truth.objects[k].id, 1001 + static_cast<int64_t>(k - 5));
      EXPECT_LT(std::hypot(truth.objects[k].x_m - person.x_m, truth.objects[k].y_m - person.y_m),
                0.6);
    }
    EXPECT_EQ(person.beams_on_object, truth.objects[5].beams_on_object +
                                          truth.objects[6].beams_on_object);
    EXPECT_GE(person.beams_on_object, 3);
    // 5 wall segments (the bottom side is cut by the door).
    ASSERT_EQ(truth.segments.size(), 5u);
    int on_walls = 0;
    for (const SegmentTruth& segment : truth.segments) {
      EXPECT_EQ(segment.id, 1);
      EXPECT_EQ(segment.kind, ObjectKind::kWall);
      on_walls += segment.beams_on_segment;
    }
    // Every beam hits something inside a closed room except those through the door; each beam
    // names its surface, and a wall beam's range is the distance to the wall.
    int through_door = 0;
    int on_objects = 0;
    for (const SimulatedBeam& beam : e.sensor.scan) {
      if (!beam.valid) {
        ++through_door;
        EXPECT_EQ(beam.segment, -1);
        EXPECT_EQ(beam.object, -1);
        continue;
      }
      EXPECT_NE(beam.segment >= 0, beam.object >= 0);
      on_objects += beam.object >= 0 ? 1 : 0;
    }
    EXPECT_GT(through_door, 0);
    EXPECT_LT(through_door, 40);
    int counted = 0;
    for (const ObjectTruth& o : truth.objects) {
      if (o.kind != ObjectKind::kPerson) counted += o.beams_on_object;
    }
    EXPECT_EQ(counted, on_objects);
    EXPECT_EQ(on_walls + on_objects + through_door, static_cast<int>(e.sensor.scan.size()));
    // Features: chair legs and the person, never a wall or a leg.
    for (const PointFeature& f : e.sensor.features) {
      const ObjectKind kind = truth.objects[static_cast<size_t>(f.object)].kind;
      EXPECT_TRUE(kind == ObjectKind::kFurniture || kind == ObjectKind::kPerson);
    }
  }
  EXPECT_EQ(frames, 41);
}

TEST(WorldSimulatorTest, WallHidesWhatStandsBehindIt) {
  Scenario s = RoomWithAPerson();
  s.duration_s = 0.5;
  StaticObjectSpec outside;
  outside.id = 50;
  outside.x_m = 8.0;
  outside.y_m = 2.0;
  outside.radius_m = 0.3;
  s.statics.push_back(outside);
  WorldSimulator world(s, 1, SensorOutput::kBoth);
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const ObjectTruth& post = e.sensor.truth.objects[4];
    ASSERT_EQ(post.id, 50);
    EXPECT_EQ(post.beams_on_object, 0);
    EXPECT_FALSE(post.visible);  // no feature through the wall
  }
}

TEST(WorldSimulatorTest, EveryMoverKindCanWalkOnLegs) {
  Scenario s;
  s.duration_s = 20.0;
  s.people = MoverBody::kLegs;
  MoverSpec constant;
  constant.id = 1;
  constant.kind = MoverKind::kConstantVelocity;
  constant.start_x_m = -5.0;
  constant.start_y_m = 3.0;
  constant.vx_mps = 1.0;
  MoverSpec waypoints;
  waypoints.id = 2;
  waypoints.kind = MoverKind::kWaypoints;
  waypoints.waypoints = {{0.0, -3.0, 0.0}, {6.0, -3.0, 5.0}, {6.0, 3.0, 0.0}};
  MoverSpec recorded;
  recorded.id = 3;
  recorded.kind = MoverKind::kTrajectory;
  recorded.trajectory = {{0.0, -6.0, 0.0}, {10.0, -6.0, 12.0}, {20.0, 6.0, 12.0}};
  MoverSpec walker;
  walker.id = 4;
  walker.kind = MoverKind::kRandomWalk;
  walker.start_x_m = 10.0;
  walker.start_y_m = 10.0;
  walker.random_walk.area_min_x_m = 5.0;
  walker.random_walk.area_min_y_m = 5.0;
  walker.random_walk.area_max_x_m = 15.0;
  walker.random_walk.area_max_y_m = 15.0;
  MoverSpec disc = constant;
  disc.id = 5;
  disc.start_y_m = -9.0;
  disc.body = MoverBody::kDisc;
  s.movers = {constant, waypoints, recorded, walker, disc};
  WorldSimulator world(s, 3, SensorOutput::kScans);
  std::map<int64_t, double> widest;
  std::map<int64_t, int> stance_changes;
  std::map<int64_t, bool> last_stance;
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const std::vector<ObjectTruth>& objects = e.sensor.truth.objects;
    ASSERT_EQ(objects.size(), 4u * 3u + 1u);
    for (size_t i = 0; i + 2 < objects.size(); i += 3) {
      ASSERT_EQ(objects[i].kind, ObjectKind::kPerson);
      const ObjectTruth& left = objects[i + 1];
      const ObjectTruth& right = objects[i + 2];
      EXPECT_EQ(left.parent_id, objects[i].id);
      EXPECT_EQ(right.parent_id, objects[i].id);
      EXPECT_DOUBLE_EQ(left.radius_m, s.legs.radius_m);
      const double apart = std::hypot(left.x_m - right.x_m, left.y_m - right.y_m);
      widest[objects[i].id] = std::max(widest[objects[i].id], apart);
      EXPECT_NEAR(objects[i].radius_m, 0.5 * apart + s.legs.radius_m, 1e-12);
      // The legs stay with the body.
      EXPECT_LT(std::hypot(left.x_m - objects[i].x_m, left.y_m - objects[i].y_m), 0.9);
      const bool moving = left.vx_mps != 0.0 || left.vy_mps != 0.0;
      if (moving != last_stance[objects[i].id]) ++stance_changes[objects[i].id];
      last_stance[objects[i].id] = moving;
    }
    EXPECT_EQ(objects.back().kind, ObjectKind::kDisc);
  }
  for (int64_t id = 1; id <= 4; ++id) {
    EXPECT_GT(widest[id], 0.45) << id;  // steps of about 0.6 m at 1 m/s
    EXPECT_LT(widest[id], 0.9) << id;
    EXPECT_GT(stance_changes[id], 10) << id;  // the left leg stops and goes: bursts
  }
}

}  // namespace
}  // namespace slammtt
