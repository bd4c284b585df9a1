// The indoor scenarios of issue 11 (office, corridor, office-hokuyo): what their headers promise,
// and nobody's legs ever touch a wall or a piece of furniture, over 20 seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "tools/world/scenario_loader.h"
#include "tools/world/scenario_report.h"

namespace slammtt {
namespace {

Scenario Load(const std::string& name) {
  return LoadScenario(std::string(SLAMMTT_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml");
}

struct Clearance {
  double legs_to_statics_m = 1e300;  // legs (and discs) to static circles and segments
  double legs_to_other_people_m = 1e300;
  double robot_to_statics_m = 1e300;
  double robot_to_legs_m = 1e300;
  std::string worst;  // where legs_to_statics_m was found
};

// Surface gaps measured directly on the truth of every scan (the laser's beams do not matter:
// a coarse beam layout keeps it fast; legs move at the scan times, which stay the same).
Clearance MeasureClearance(Scenario s, uint64_t seed) {
  s.laser.resolution_deg = 45.0;
  s.laser.artefacts = LaserArtefactSpec{};
  constexpr double kRobotRadiusM = 0.26;
  WorldSimulator world(s, seed, SensorOutput::kScans);
  Clearance c;
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const TruthSnapshot& truth = e.sensor.truth;
    const Pose2D& robot = truth.robot.pose;
    for (const SegmentTruth& wall : truth.segments) {
      c.robot_to_statics_m =
          std::min(c.robot_to_statics_m,
                   std::sqrt(SquaredDistanceToSegment(robot.x_m, robot.y_m, wall.segment)) -
                       kRobotRadiusM);
    }
    for (const ObjectTruth& o : truth.objects) {
      if (o.is_static) {
        c.robot_to_statics_m = std::min(
            c.robot_to_statics_m,
            std::hypot(o.x_m - robot.x_m, o.y_m - robot.y_m) - o.radius_m - kRobotRadiusM);
        continue;
      }
      if (o.kind == ObjectKind::kPerson) continue;
      c.robot_to_legs_m =
          std::min(c.robot_to_legs_m,
                   std::hypot(o.x_m - robot.x_m, o.y_m - robot.y_m) - o.radius_m - kRobotRadiusM);
      for (const SegmentTruth& wall : truth.segments) {
        const double gap =
            std::sqrt(SquaredDistanceToSegment(o.x_m, o.y_m, wall.segment)) - o.radius_m;
        if (gap < c.legs_to_statics_m) {
          c.legs_to_statics_m = gap;
          c.worst = std::to_string(o.id) + " and wall " + std::to_string(wall.id) + " at " +
                    std::to_string(e.time_us * 1e-6) + " s";
        }
      }
      for (const ObjectTruth& p : truth.objects) {
        if (&p == &o || p.kind == ObjectKind::kPerson) continue;
        const double gap = std::hypot(o.x_m - p.x_m, o.y_m - p.y_m) - o.radius_m - p.radius_m;
        if (p.is_static) {
          if (gap < c.legs_to_statics_m) {
            c.legs_to_statics_m = gap;
            c.worst = std::to_string(o.id) + " and " + std::to_string(p.id) + " at " +
                      std::to_string(e.time_us * 1e-6) + " s";
          }
        } else if (p.parent_id != o.parent_id || o.kind == ObjectKind::kDisc) {
          c.legs_to_other_people_m = std::min(c.legs_to_other_people_m, gap);
        }
      }
    }
  }
  return c;
}

TEST(IndoorScenariosTest, NobodysLegsEverTouchAWallOrFurnitureOver20Seeds) {
  for (const std::string name : {"office", "corridor", "office-hokuyo"}) {
    const Scenario s = Load(name);
    double worst_statics = 1e300;
    double worst_people = 1e300;
    double worst_robot_statics = 1e300;
    double worst_robot_legs = 1e300;
    for (uint64_t seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      const Clearance c = MeasureClearance(s, seed);
      EXPECT_GT(c.legs_to_statics_m, 0.05) << c.worst;
      EXPECT_GT(c.legs_to_other_people_m, 0.05);
      EXPECT_GT(c.robot_to_statics_m, 0.05);
      EXPECT_GT(c.robot_to_legs_m, 0.05);
      worst_statics = std::min(worst_statics, c.legs_to_statics_m);
      worst_people = std::min(worst_people, c.legs_to_other_people_m);
      worst_robot_statics = std::min(worst_robot_statics, c.robot_to_statics_m);
      worst_robot_legs = std::min(worst_robot_legs, c.robot_to_legs_m);
    }
    std::cout << name << ": closest over seeds 1-20: legs-static " << worst_statics
              << " m, legs-other person " << worst_people << " m, robot-static "
              << worst_robot_statics << " m, robot-legs " << worst_robot_legs << " m\n";
  }
}

TEST(IndoorScenariosTest, OfficeIsRoomsDoorsFurnitureAndPeopleOnLegs) {
  const Scenario s = Load("office");
  EXPECT_EQ(s.duration_s, 120.0);
  EXPECT_EQ(s.people, MoverBody::kLegs);
  // The RPLIDAR A2 as its driver delivers it.
  EXPECT_EQ(s.laser.fov_deg, 360.0);
  EXPECT_EQ(s.laser.rate_hz, 10.0);
  EXPECT_EQ(s.laser.max_range_m, 12.0);
  EXPECT_EQ(s.laser.artefacts.sample_rate_hz, 4000.0);
  EXPECT_GT(s.laser.artefacts.mixed_pixel_probability, 0.0);
  // About 12 x 8 m: the extent of every wall.
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
  std::set<ObjectKind> kinds;
  int openings = 0;
  int chairs = 0;
  for (const StaticObjectSpec& o : s.statics) {
    kinds.insert(o.kind);
    openings += static_cast<int>(o.openings.size());
    chairs += o.shape == StaticShape::kLegs ? 1 : 0;
    for (const PlanarPoint& v : o.vertices) {
      min_x = std::min(min_x, v.x_m);
      max_x = std::max(max_x, v.x_m);
      min_y = std::min(min_y, v.y_m);
      max_y = std::max(max_y, v.y_m);
    }
  }
  EXPECT_EQ(max_x - min_x, 12.0);
  EXPECT_EQ(max_y - min_y, 8.0);
  EXPECT_EQ(kinds.size(), 3u);  // walls, furniture and a post
  EXPECT_GE(openings, 8);       // doors and the corridor's two open ends
  EXPECT_GE(chairs, 8);
  EXPECT_GE(s.movers.size(), 4u);
  EXPECT_LE(s.movers.size(), 6u);

  const ScenarioReport r = ReportScenario(s, 7);
  EXPECT_EQ(r.scans, 1201);
  EXPECT_GE(r.robot_max_speed_mps, 0.25);
  EXPECT_LE(r.robot_max_speed_mps, 0.4);
  EXPECT_GE(r.robot_path_m, 25.0);
  // What the A2 sees: mostly straight structure, legs as one or two beams, some mixed pixels.
  EXPECT_GT(r.beams_on_segments, r.valid_beams * 9 / 10);
  EXPECT_GT(r.beams_on_legs, 0);
  EXPECT_GT(r.mixed_pixels, 0);
  EXPECT_GT(r.dropouts, 0);
  EXPECT_GT(r.legs_with_3_beams, 0);
  EXPECT_GT(r.legs_hidden_while_other_seen, 0);  // legs hide each other
  // People enter and leave (exist for less than the run), stop and walk in pairs.
  int short_lived = 0;
  for (const MoverReport& m : r.movers) short_lived += m.exists_s < 100.0 ? 1 : 0;
  EXPECT_GE(short_lived, 4);
  int waits = 0;
  for (const MoverSpec& m : s.movers) {
    for (const MoverWaypoint& w : m.waypoints) waits += w.wait_s >= 10.0 ? 1 : 0;
  }
  EXPECT_GE(waits, 5);
}

TEST(IndoorScenariosTest, OfficeHokuyoIsTheSameOfficeSeenByA270DegreeScanner) {
  const Scenario office = Load("office");
  const Scenario hokuyo = Load("office-hokuyo");
  EXPECT_NEAR(hokuyo.laser.fov_deg, 270.0, 0.5);
  EXPECT_NEAR(hokuyo.laser.resolution_deg, 0.352, 0.001);
  EXPECT_EQ(LaserBeamAngles(hokuyo.laser).size(), 768u);  // as leg_tracker_training's scans
  EXPECT_EQ(hokuyo.laser.artefacts.sample_rate_hz, 0.0);
  ASSERT_EQ(hokuyo.statics.size(), office.statics.size());
  for (size_t i = 0; i < office.statics.size(); ++i) {
    EXPECT_EQ(hokuyo.statics[i].id, office.statics[i].id);
    EXPECT_EQ(hokuyo.statics[i].x_m, office.statics[i].x_m);
    EXPECT_EQ(hokuyo.statics[i].vertices.size(), office.statics[i].vertices.size());
  }
  ASSERT_EQ(hokuyo.movers.size(), office.movers.size());
  for (size_t i = 0; i < office.movers.size(); ++i) {
    EXPECT_EQ(hokuyo.movers[i].id, office.movers[i].id);
    EXPECT_EQ(hokuyo.movers[i].waypoints.size(), office.movers[i].waypoints.size());
    EXPECT_EQ(hokuyo.movers[i].appear_s, office.movers[i].appear_s);
  }
  EXPECT_EQ(hokuyo.robot.waypoints.size(), office.robot.waypoints.size());
  // The finer scanner puts more beams on each leg it sees.
  const ScenarioReport a2 = ReportScenario(office, 7);
  const ScenarioReport fine = ReportScenario(hokuyo, 7);
  EXPECT_GT(static_cast<double>(fine.beams_on_legs_in_view) / fine.legs_with_beams,
            static_cast<double>(a2.beams_on_legs_in_view) / a2.legs_with_beams);
}

TEST(IndoorScenariosTest, CorridorIsLongAndPeopleWalkTowardsAndAwayFromTheRobot) {
  const Scenario s = Load("corridor");
  EXPECT_EQ(s.people, MoverBody::kLegs);
  ASSERT_GE(s.statics.size(), 2u);
  EXPECT_EQ(s.statics[0].vertices.back().x_m - s.statics[0].vertices.front().x_m, 30.0);
  EXPECT_GE(s.statics[0].openings.size() + s.statics[1].openings.size(), 6u);
  WorldSimulator world(s, 7, SensorOutput::kScans);
  int towards = 0;
  int away = 0;
  while (!world.Done()) {
    const WorldEvent e = world.Next();
    if (e.kind != WorldEvent::Kind::kSensor) continue;
    const TruthSnapshot& truth = e.sensor.truth;
    const double robot_vx = truth.robot.linear_mps * std::cos(truth.robot.pose.heading_rad);
    for (const ObjectTruth& o : truth.objects) {
      if (o.kind != ObjectKind::kPerson || std::abs(o.vx_mps) < 0.5) continue;
      const double ahead = (o.x_m - truth.robot.pose.x_m) * (robot_vx >= 0.0 ? 1.0 : -1.0);
      const double closing = (o.vx_mps - robot_vx) * (o.x_m > truth.robot.pose.x_m ? -1 : 1);
      if (ahead > 0.0 && closing > 0.0) ++towards;
      if (o.vx_mps * robot_vx > 0.0) ++away;
    }
  }
  EXPECT_GT(towards, 100);  // person-scans walking towards the robot
  EXPECT_GT(away, 100);     // ... and in its direction of travel
  const ScenarioReport r = ReportScenario(s, 7);
  EXPECT_GE(r.robot_path_m, 35.0);
  EXPECT_GT(r.beams_on_walls, r.valid_beams * 9 / 10);
}

}  // namespace
}  // namespace slammtt
