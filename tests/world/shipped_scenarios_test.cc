// Every shipped scenario loads, runs, and stays fair for an estimator: no object ever overlaps
// another or the robot, landmarks and movers are in view, and each scenario reproduces what its
// header promises (the paper's velocities, sensor and occlusion window for s1, ...). The figures
// come from full runs of the simulator (ScenarioReport), for several seeds where the scenario
// has random walkers.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include "tools/world/scenario_loader.h"
#include "tools/world/scenario_report.h"

namespace slammtt {
namespace {

const std::vector<std::string>& ShippedNames() {
  static const std::vector<std::string> names = {
      "s1-crossing", "s2-lobby", "s3-no-static", "rplidar-a2", "crowd-zara02",
      "office",      "corridor", "office-hokuyo"};
  return names;
}

std::string ScenarioPath(const std::string& name) {
  return std::string(SLAMMTT_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

Scenario Load(const std::string& name) { return LoadScenario(ScenarioPath(name)); }

TEST(ShippedScenariosTest, EveryScenarioLoadsStartsWithItsDescriptionAndRunsInEveryOutputMode) {
  for (const std::string& name : ShippedNames()) {
    SCOPED_TRACE(name);
    std::ifstream in(ScenarioPath(name));
    std::string first_line;
    std::getline(in, first_line);
    EXPECT_EQ(first_line.rfind("# " + name + ": ", 0), 0u) << first_line;
    Scenario scenario = Load(name);
    EXPECT_EQ(scenario.name, name);
    EXPECT_TRUE(FindScenarioProblems(scenario).empty());
    scenario.duration_s = 3.0;
    for (SensorOutput output :
         {SensorOutput::kFeatures, SensorOutput::kScans, SensorOutput::kBoth}) {
      WorldSimulator world(scenario, 1, output);
      int sensor_frames = 0;
      int odometry = 0;
      while (!world.Done()) {
        const WorldEvent e = world.Next();
        if (e.kind == WorldEvent::Kind::kSensor) {
          ++sensor_frames;
          EXPECT_EQ(e.sensor.has_scan, output != SensorOutput::kFeatures);
          EXPECT_EQ(e.sensor.has_features, output != SensorOutput::kScans);
        } else {
          ++odometry;
        }
      }
      EXPECT_EQ(sensor_frames, static_cast<int>(std::floor(3.0 * scenario.laser.rate_hz)) + 1);
      EXPECT_EQ(odometry, static_cast<int>(std::floor(3.0 * scenario.odometry.rate_hz)) + 1);
    }
  }
}

// No two things ever overlap: movers keep `min_gap_m` from each other (surfaces), from static
// objects and from the robot's body.
void ExpectNoOverlaps(const ScenarioReport& r, double min_gap_m) {
  EXPECT_GE(r.mover_mover.gap_m, min_gap_m)
      << r.mover_mover.id_a << " and " << r.mover_mover.id_b << " at " << r.mover_mover.time_s;
  EXPECT_GE(r.mover_static.gap_m, min_gap_m)
      << r.mover_static.id_a << " and " << r.mover_static.id_b << " at " << r.mover_static.time_s;
  EXPECT_GE(r.robot_mover.gap_m, min_gap_m) << r.robot_mover.id_b << " at " << r.robot_mover.time_s;
  EXPECT_GE(r.robot_static.gap_m, min_gap_m)
      << r.robot_static.id_b << " at " << r.robot_static.time_s;
}

TEST(ShippedScenariosTest, S1CrossingIsThePapersFirstSimulation) {
  const Scenario s = Load("s1-crossing");
  EXPECT_EQ(s.duration_s, 120.0);
  EXPECT_EQ(s.output, SensorOutput::kFeatures);
  EXPECT_EQ(s.laser.fov_deg, 180.0);
  EXPECT_EQ(s.laser.max_range_m, 30.0);
  EXPECT_EQ(s.laser.rate_hz, 8.0);
  EXPECT_EQ(s.features.range_noise_m, 0.2);
  EXPECT_EQ(s.features.bearing_noise_deg, 2.0);
  // T1..T5 of the paper, constant velocity for the whole run.
  const std::vector<std::pair<double, double>> paper = {
      {0.625, 0.625}, {0.625, 0.0}, {-0.1, -0.75}, {-0.25, -0.8}, {-0.75, 0.6}};
  ASSERT_EQ(s.movers.size(), paper.size());
  for (size_t i = 0; i < paper.size(); ++i) {
    EXPECT_EQ(s.movers[i].kind, MoverKind::kConstantVelocity);
    EXPECT_EQ(s.movers[i].vx_mps, paper[i].first);
    EXPECT_EQ(s.movers[i].vy_mps, paper[i].second);
    EXPECT_EQ(s.movers[i].appear_s, 0.0);
    EXPECT_TRUE(std::isinf(s.movers[i].disappear_s));
  }
  EXPECT_GE(s.statics.size(), 20u);

  const ScenarioReport r = ReportScenario(s, 7);
  EXPECT_EQ(r.scans, 961);
  EXPECT_LE(r.robot_max_speed_mps, kMaxRobotSpeedMps);
  EXPECT_GE(r.robot_max_speed_mps, 1.99);  // "up to 2 m/s"
  ExpectNoOverlaps(r, 0.5);
  EXPECT_GE(r.min_statics_visible, 3);
  EXPECT_GE(r.mean_statics_visible, 6.0);
  // The paper's occlusions between movers at steps 550-650 (8 Hz: 68.75-81.25 s).
  int mover_mover_in_window = 0;
  std::set<int64_t> hidden;
  for (const OcclusionEpisode& e : r.occlusions) {
    if (e.occluder_is_static || e.occluder_id < 0) continue;
    if (e.start_s >= 68.75 - 1.5 && e.end_s <= 81.25) {
      ++mover_mover_in_window;
      hidden.insert(e.id);
    }
  }
  EXPECT_GE(mover_mover_in_window, 5);
  EXPECT_GE(hidden.size(), 3u);
  // Every mover is seen long enough to be tracked, and no occlusion outlasts the paper's track
  // removal time (3.5 s).
  ASSERT_EQ(r.movers.size(), 5u);
  for (const MoverReport& m : r.movers) {
    EXPECT_GE(m.visible_s, 25.0) << m.id;
    EXPECT_GE(m.longest_visible_s, 12.0) << m.id;
    EXPECT_LT(m.longest_occlusion_s, 3.5) << m.id;
  }
}

TEST(ShippedScenariosTest, S2LobbyHasStationaryObjectsAndPeopleWhoTurnEnterAndLeave) {
  const Scenario s = Load("s2-lobby");
  EXPECT_EQ(s.output, SensorOutput::kScans);
  EXPECT_GE(s.statics.size(), 10u);
  int random_walkers = 0;
  int entering = 0;
  int leaving = 0;
  int about_turns = 0;  // waypoint paths that go back the way they came
  for (const MoverSpec& m : s.movers) {
    random_walkers += m.kind == MoverKind::kRandomWalk && m.random_walk.max_turn_rad >= M_PI - 1e-9;
    entering += m.appear_s > 0.0;
    leaving += m.kind == MoverKind::kWaypoints && m.at_end == PathEnd::kLeave;
    for (size_t k = 2; k < m.waypoints.size(); ++k) {
      about_turns += m.waypoints[k].x_m == m.waypoints[k - 2].x_m &&
                     m.waypoints[k].y_m == m.waypoints[k - 2].y_m;
    }
  }
  EXPECT_GE(random_walkers, 2);
  EXPECT_GE(entering, 4);
  EXPECT_GE(leaving, 4);
  EXPECT_GE(about_turns, 2);
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    const ScenarioReport r = ReportScenario(s, seed);
    ExpectNoOverlaps(r, 0.3);
    EXPECT_GE(r.min_statics_visible, 3);
    int behind_static = 0;
    int behind_person = 0;
    for (const OcclusionEpisode& e : r.occlusions) {
      behind_static += e.occluder_is_static;
      behind_person += !e.occluder_is_static && e.occluder_id >= 0;
    }
    EXPECT_GE(behind_static, 5);
    EXPECT_GE(behind_person, 3);
    for (const MoverReport& m : r.movers) EXPECT_GE(m.visible_s, 10.0) << m.id;
  }
}

TEST(ShippedScenariosTest, S3HasNoStaticObjectButMoversAlwaysInView) {
  const Scenario s = Load("s3-no-static");
  EXPECT_TRUE(s.statics.empty());
  const ScenarioReport r = ReportScenario(s, 7);
  EXPECT_EQ(r.min_statics_visible, 0);
  EXPECT_EQ(r.mean_statics_visible, 0.0);
  EXPECT_GE(r.min_movers_visible, 3);
  ExpectNoOverlaps(r, 0.5);
  for (const MoverReport& m : r.movers) {
    EXPECT_GE(m.visible_s, 15.0) << m.id;
    EXPECT_LT(m.longest_occlusion_s, 3.5) << m.id;
  }
}

TEST(ShippedScenariosTest, RplidarA2IsTheRealRobotsSetting) {
  const Scenario s = Load("rplidar-a2");
  EXPECT_EQ(s.laser.fov_deg, 360.0);
  EXPECT_NEAR(s.laser.resolution_deg, 0.9, 0.05);
  EXPECT_EQ(s.laser.rate_hz, 10.0);
  EXPECT_EQ(LaserBeamAngles(s.laser).size(), 400u);
  EXPECT_EQ(s.robot.speed_mps, 0.25);
  for (const MoverSpec& m : s.movers) EXPECT_NEAR(m.speed_mps, 1.5, 0.25) << m.id;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(seed);
    const ScenarioReport r = ReportScenario(s, seed);
    EXPECT_NEAR(r.robot_max_speed_mps, 0.25, 1e-12);
    ExpectNoOverlaps(r, 0.3);
    EXPECT_GE(r.min_statics_visible, 3);
    EXPECT_GE(r.min_movers_visible, 2);
    int behind_person = 0;
    for (const OcclusionEpisode& e : r.occlusions) {
      behind_person += !e.occluder_is_static && e.occluder_id >= 0;
    }
    EXPECT_GE(behind_person, 3);
  }
}

TEST(ShippedScenariosTest, CrowdZara02MovesRealPedestriansAroundTheA2Robot) {
  const Scenario s = Load("crowd-zara02");
  const Scenario a2 = Load("rplidar-a2");
  EXPECT_EQ(s.laser.fov_deg, a2.laser.fov_deg);
  EXPECT_EQ(s.laser.resolution_deg, a2.laser.resolution_deg);
  EXPECT_EQ(s.laser.rate_hz, a2.laser.rate_hz);
  EXPECT_EQ(s.laser.max_range_m, a2.laser.max_range_m);
  EXPECT_EQ(s.robot.speed_mps, a2.robot.speed_mps);
  EXPECT_GE(s.movers.size(), 50u);
  for (const MoverSpec& m : s.movers) EXPECT_EQ(m.kind, MoverKind::kTrajectory);
  const ScenarioReport r = ReportScenario(s, 7);
  // Recorded people walk in couples closer than two body radii: they may overlap each other,
  // but nobody walks through a static object or comes near the robot.
  EXPECT_GE(r.mover_static.gap_m, 0.1) << r.mover_static.id_b << " at " << r.mover_static.time_s;
  EXPECT_GE(r.robot_mover.gap_m, 0.5);
  EXPECT_GE(r.robot_static.gap_m, 0.2);
  EXPECT_GE(r.min_statics_visible, 3);
  EXPECT_GE(r.mean_movers_visible, 5.0);
  int entering_or_leaving = 0;
  int standing = 0;
  for (const MoverReport& m : r.movers) entering_or_leaving += m.exists_s < 119.0;
  for (const MoverSpec& m : s.movers) {
    const TimedPoint& a = m.trajectory.front();
    const TimedPoint& b = m.trajectory.back();
    standing += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m) / (b.t_s - a.t_s) < 0.2;
  }
  EXPECT_GE(entering_or_leaving, 40);
  EXPECT_GE(standing, 3);  // groups standing in front of the shop
}

}  // namespace
}  // namespace slammtt
