// Motion models of the movers: constant velocity, waypoints (waits, leave, loop), timed
// trajectories (interpolation, enter and leave), random walks (deterministic per seed, turning).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tools/world/mover_path.h"
#include "tools/world/portable_random.h"
#include "tools/world/recorded_crowd.h"

namespace slammtt {
namespace {

MoverPath Build(const MoverSpec& spec, double horizon_s = 100.0, uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  return BuildMoverPath(spec, horizon_s, rng);
}

TEST(MoverPathTest, ConstantVelocityFollowsPaperEq7) {
  MoverSpec spec;
  spec.kind = MoverKind::kConstantVelocity;
  spec.start_x_m = 1.0;
  spec.start_y_m = -2.0;
  spec.vx_mps = 0.625;
  spec.vy_mps = -0.75;
  spec.appear_s = 5.0;
  spec.disappear_s = 50.0;
  const MoverPath path = Build(spec);
  EXPECT_FALSE(path.ExistsAt(4.99));
  EXPECT_TRUE(path.ExistsAt(5.0));
  EXPECT_TRUE(path.ExistsAt(49.99));
  EXPECT_FALSE(path.ExistsAt(50.0));
  const MoverState s = path.StateAt(17.0);
  EXPECT_NEAR(s.x_m, 1.0 + 0.625 * 12.0, 1e-12);
  EXPECT_NEAR(s.y_m, -2.0 - 0.75 * 12.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.vx_mps, 0.625);
  EXPECT_DOUBLE_EQ(s.vy_mps, -0.75);
}

TEST(MoverPathTest, ConstantVelocityKeepsItsVelocityAtTheHorizon) {
  MoverSpec spec;
  spec.kind = MoverKind::kConstantVelocity;
  spec.vx_mps = 1.0;
  const MoverPath path = Build(spec, 30.0);
  EXPECT_DOUBLE_EQ(path.StateAt(30.0).vx_mps, 1.0);
  EXPECT_NEAR(path.StateAt(30.0).x_m, 30.0, 1e-12);
}

TEST(MoverPathTest, WaypointsWithWaitsAndStay) {
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 2.0;
  spec.appear_s = 1.0;
  spec.waypoints = {MoverWaypoint{0.0, 0.0, 0.0}, MoverWaypoint{4.0, 0.0, 3.0},
                    MoverWaypoint{4.0, 6.0, 0.0}};
  const MoverPath path = Build(spec);
  // 0 -> 4 m east in 2 s (arrive t = 3), wait 3 s (to t = 6), 6 m north in 3 s (arrive t = 9).
  EXPECT_NEAR(path.StateAt(2.0).x_m, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(path.StateAt(2.0).vx_mps, 2.0);
  EXPECT_NEAR(path.StateAt(4.5).x_m, 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(path.StateAt(4.5).vx_mps, 0.0);
  EXPECT_DOUBLE_EQ(path.StateAt(4.5).vy_mps, 0.0);
  EXPECT_NEAR(path.StateAt(7.5).y_m, 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(path.StateAt(7.5).vy_mps, 2.0);
  EXPECT_NEAR(path.StateAt(50.0).y_m, 6.0, 1e-12);
  EXPECT_TRUE(path.ExistsAt(50.0));  // stays
}

TEST(MoverPathTest, WaypointMoverLeavesOnArrival) {
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 1.0;
  spec.at_end = PathEnd::kLeave;
  spec.waypoints = {MoverWaypoint{0.0, 0.0, 0.0}, MoverWaypoint{5.0, 0.0, 0.0}};
  const MoverPath path = Build(spec);
  EXPECT_TRUE(path.ExistsAt(4.9));
  EXPECT_FALSE(path.ExistsAt(5.0));
}

TEST(MoverPathTest, WaypointLoopComesBack) {
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 1.0;
  spec.at_end = PathEnd::kLoop;
  spec.waypoints = {MoverWaypoint{0.0, 0.0, 0.0}, MoverWaypoint{3.0, 0.0, 0.0},
                    MoverWaypoint{3.0, 4.0, 0.0}};
  const MoverPath path = Build(spec, 60.0);
  // One lap: 3 + 4 + 5 = 12 s. After one lap it is back at the start, heading east again.
  const MoverState lap = path.StateAt(13.0);
  EXPECT_NEAR(lap.x_m, 1.0, 1e-9);
  EXPECT_NEAR(lap.y_m, 0.0, 1e-9);
  EXPECT_NEAR(lap.vx_mps, 1.0, 1e-9);
  // On the closing diagonal (3, 4) -> (0, 0) at t = 9.5: halfway.
  EXPECT_NEAR(path.StateAt(9.5).x_m, 1.5, 1e-9);
  EXPECT_NEAR(path.StateAt(9.5).vx_mps, -0.6, 1e-9);
  EXPECT_TRUE(path.ExistsAt(59.0));
}

TEST(MoverPathTest, WaypointLoopRepeatsEveryLapExactly) {
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 1.0;
  spec.appear_s = 2.0;
  spec.at_end = PathEnd::kLoop;
  spec.waypoints = {MoverWaypoint{0.0, 0.0, 1.0}, MoverWaypoint{3.0, 0.0, 0.5},
                    MoverWaypoint{3.0, 4.0, 0.0}};
  const MoverPath path = Build(spec, 1e6);
  // Lap from t = 3 (after the first wait): 3 m, 0.5 s wait, 4 m, 5 m back, 1 s wait = 13.5 s.
  ASSERT_TRUE(path.repeat_from_s().has_value());
  EXPECT_EQ(*path.repeat_from_s(), 3.0);
  EXPECT_EQ(path.knots().back().t_s, 16.5);
  EXPECT_LE(path.knots().size(), 8u);  // one lap, whatever the horizon
  for (const double t : {3.0, 4.25, 6.2, 9.0, 15.9, 16.2}) {
    for (const double laps : {1.0, 7.0, 70000.0}) {
      SCOPED_TRACE(std::to_string(t) + " + " + std::to_string(laps) + " laps");
      const MoverState first = path.StateAt(t);
      const MoverState later = path.StateAt(t + laps * 13.5);
      EXPECT_NEAR(later.x_m, first.x_m, 1e-9);
      EXPECT_NEAR(later.y_m, first.y_m, 1e-9);
      EXPECT_NEAR(later.vx_mps, first.vx_mps, 1e-9);
      EXPECT_NEAR(later.vy_mps, first.vy_mps, 1e-9);
    }
  }
  // Standing at the first waypoint during its wait, at the end of every lap.
  EXPECT_DOUBLE_EQ(path.StateAt(16.0 + 13.5).x_m, 0.0);
  EXPECT_DOUBLE_EQ(path.StateAt(16.0 + 13.5).vx_mps, 0.0);
}

TEST(MoverPathTest, WaypointLoopOfATinyLapCostsOneLapNotMemoryPerLap) {
  // A lap of 2 ns over a 10^6 s run was 5 * 10^14 knots (out of memory); now it is one lap.
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 1.0;
  spec.at_end = PathEnd::kLoop;
  spec.waypoints = {MoverWaypoint{0.0, 0.0, 0.0}, MoverWaypoint{0.0, 1e-9, 0.0}};
  const MoverPath path = Build(spec, 1e6);
  EXPECT_EQ(path.knots().size(), 3u);
  const MoverState s = path.StateAt(654321.123);
  EXPECT_EQ(s.x_m, 0.0);
  EXPECT_GE(s.y_m, 0.0);
  EXPECT_LE(s.y_m, 1e-9);
  EXPECT_NEAR(std::abs(s.vy_mps), 1.0, 1e-6);
  // Every waypoint at one place and no wait: a lap that takes no time is standing still.
  spec.waypoints = {MoverWaypoint{2.0, 1.0, 0.0}, MoverWaypoint{2.0, 1.0, 0.0}};
  const MoverPath standing = Build(spec, 1e6);
  EXPECT_FALSE(standing.repeat_from_s().has_value());
  EXPECT_EQ(standing.StateAt(5e5).x_m, 2.0);
  EXPECT_EQ(standing.StateAt(5e5).vx_mps, 0.0);
}

TEST(MoverPathTest, LoopMustCloseAtAKnot) {
  const std::vector<TimedPoint> closed = {TimedPoint{0.0, 0.0, 0.0}, TimedPoint{1.0, 1.0, 0.0},
                                          TimedPoint{2.0, 0.0, 0.0}};
  EXPECT_NO_THROW(MoverPath(closed, 0.0, 10.0, 0.0));
  EXPECT_THROW(MoverPath(closed, 0.0, 10.0, 0.5), std::invalid_argument);  // not a knot
  EXPECT_THROW(MoverPath(closed, 0.0, 10.0, 1.0), std::invalid_argument);  // elsewhere
  EXPECT_THROW(MoverPath(closed, 0.0, 10.0, 2.0), std::invalid_argument);  // the last knot
}

TEST(MoverPathTest, TrajectoryIsInterpolatedAndEntersAndLeaves) {
  MoverSpec spec;
  spec.kind = MoverKind::kTrajectory;
  spec.trajectory = {TimedPoint{2.0, 0.0, 0.0}, TimedPoint{4.0, 2.0, 0.0},
                     TimedPoint{6.0, 2.0, 2.0}};
  const MoverPath path = Build(spec);
  EXPECT_FALSE(path.ExistsAt(1.99));
  EXPECT_TRUE(path.ExistsAt(2.0));
  EXPECT_TRUE(path.ExistsAt(6.0));  // the last sample is included
  EXPECT_FALSE(path.ExistsAt(6.01));
  const MoverState a = path.StateAt(3.0);
  EXPECT_NEAR(a.x_m, 1.0, 1e-12);
  EXPECT_NEAR(a.y_m, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.vx_mps, 1.0);
  const MoverState b = path.StateAt(5.5);
  EXPECT_NEAR(b.x_m, 2.0, 1e-12);
  EXPECT_NEAR(b.y_m, 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(b.vy_mps, 1.0);
  // Exactly at a knot: the velocity of the segment that starts there.
  EXPECT_DOUBLE_EQ(path.StateAt(4.0).vy_mps, 1.0);
  EXPECT_DOUBLE_EQ(path.StateAt(4.0).vx_mps, 0.0);
}

TEST(MoverPathTest, PathRejectsNonIncreasingKnots) {
  EXPECT_THROW(MoverPath({TimedPoint{1.0, 0, 0}, TimedPoint{1.0, 1, 1}}, 0.0, 10.0),
               std::invalid_argument);
  EXPECT_THROW(MoverPath({}, 0.0, 10.0), std::invalid_argument);
}

MoverSpec RandomWalker() {
  MoverSpec spec;
  spec.id = 7;
  spec.kind = MoverKind::kRandomWalk;
  spec.speed_mps = 1.5;
  spec.random_walk.mean_leg_s = 3.0;
  spec.random_walk.max_turn_rad = M_PI;
  spec.random_walk.area_min_x_m = -10.0;
  spec.random_walk.area_min_y_m = -8.0;
  spec.random_walk.area_max_x_m = 10.0;
  spec.random_walk.area_max_y_m = 8.0;
  return spec;
}

TEST(MoverPathTest, RandomWalkIsTheSameForTheSameSeedAndDiffersForAnother) {
  const MoverPath a = Build(RandomWalker(), 120.0, 42);
  const MoverPath b = Build(RandomWalker(), 120.0, 42);
  const MoverPath c = Build(RandomWalker(), 120.0, 43);
  ASSERT_EQ(a.knots().size(), b.knots().size());
  for (size_t i = 0; i < a.knots().size(); ++i) {
    EXPECT_EQ(a.knots()[i].t_s, b.knots()[i].t_s);
    EXPECT_EQ(a.knots()[i].x_m, b.knots()[i].x_m);
    EXPECT_EQ(a.knots()[i].y_m, b.knots()[i].y_m);
  }
  bool differs = a.knots().size() != c.knots().size();
  for (size_t i = 0; !differs && i < a.knots().size(); ++i) {
    differs = a.knots()[i].x_m != c.knots()[i].x_m;
  }
  EXPECT_TRUE(differs);
}

TEST(MoverPathTest, RandomWalkTurnsSharplyKeepsSpeedAndStaysInItsArea) {
  const MoverSpec spec = RandomWalker();
  const MoverPath path = Build(spec, 300.0, 5);
  const std::vector<TimedPoint>& k = path.knots();
  ASSERT_GT(k.size(), 40u);
  double largest_turn = 0.0;
  for (size_t i = 0; i + 1 < k.size(); ++i) {
    const double length = std::hypot(k[i + 1].x_m - k[i].x_m, k[i + 1].y_m - k[i].y_m);
    EXPECT_NEAR(length / (k[i + 1].t_s - k[i].t_s), spec.speed_mps, 1e-9);
    EXPECT_GE(k[i + 1].x_m, -10.0);
    EXPECT_LE(k[i + 1].x_m, 10.0);
    EXPECT_GE(k[i + 1].y_m, -8.0);
    EXPECT_LE(k[i + 1].y_m, 8.0);
    if (i > 0) {
      const double before = std::atan2(k[i].y_m - k[i - 1].y_m, k[i].x_m - k[i - 1].x_m);
      const double after = std::atan2(k[i + 1].y_m - k[i].y_m, k[i + 1].x_m - k[i].x_m);
      largest_turn = std::max(largest_turn, std::abs(WrapAngle(after - before)));
    }
  }
  EXPECT_GT(largest_turn, 150.0 * M_PI / 180.0);
}

TEST(MoverPathTest, RandomWalkWithCertainReversalWalksBackAndForth) {
  MoverSpec spec = RandomWalker();
  spec.random_walk.reverse_probability = 1.0;
  spec.random_walk.area_min_x_m = -1000.0;
  spec.random_walk.area_max_x_m = 1000.0;
  spec.random_walk.area_min_y_m = -1000.0;
  spec.random_walk.area_max_y_m = 1000.0;
  const MoverPath path = Build(spec, 60.0, 9);
  const std::vector<TimedPoint>& k = path.knots();
  ASSERT_GT(k.size(), 4u);
  for (size_t i = 0; i + 1 < k.size(); ++i) {
    EXPECT_NEAR(k[i + 1].y_m, 0.0, 1e-9);  // heading 0 and pi only: on the x axis
    if (i > 0) {
      const double before = k[i].x_m - k[i - 1].x_m;
      const double after = k[i + 1].x_m - k[i].x_m;
      EXPECT_LT(before * after, 0.0);  // 180-degree turn at every leg
    }
  }
}

TEST(MoverPathTest, RandomWalkInATinyAreaStandsInsteadOfLoopingForever) {
  MoverSpec spec = RandomWalker();
  spec.start_x_m = 1.0;
  spec.start_y_m = 1.0;
  spec.random_walk.area_min_x_m = 1.0;
  spec.random_walk.area_min_y_m = 1.0;
  spec.random_walk.area_max_x_m = 1.0 + 1e-9;
  spec.random_walk.area_max_y_m = 1.0 + 1e-9;
  const MoverPath path = Build(spec, 30.0, 3);
  EXPECT_GT(path.knots().size(), 2u);
  EXPECT_GE(path.knots().back().t_s, 30.0);
  EXPECT_NEAR(path.StateAt(20.0).x_m, 1.0, 1e-6);
}

TEST(RecordedCrowdTest, WindowShiftTransformAndCap) {
  std::vector<RecordedTrack> tracks(3);
  tracks[0].id = 5;
  tracks[0].points = {TimedPoint{10.0, 1.0, 0.0}, TimedPoint{10.4, 2.0, 0.0},
                      TimedPoint{10.8, 3.0, 0.0}};
  tracks[1].id = 2;
  tracks[1].points = {TimedPoint{12.0, 0.0, 1.0}, TimedPoint{12.4, 0.0, 2.0}};
  tracks[2].id = 9;  // one sample inside the window only: skipped
  tracks[2].points = {TimedPoint{1.0, 0.0, 0.0}, TimedPoint{10.0, 0.0, 0.0}};
  CrowdImportSpec spec;
  spec.window_start_s = 10.0;
  spec.window_end_s = 20.0;
  spec.rotation_rad = M_PI / 2;
  spec.offset_x_m = 100.0;
  spec.offset_y_m = 50.0;
  spec.id_offset = 1000;
  const std::vector<MoverSpec> movers = MoversFromRecordedTracks(tracks, spec);
  ASSERT_EQ(movers.size(), 2u);
  EXPECT_EQ(movers[0].id, 1005);  // appears first
  EXPECT_EQ(movers[1].id, 1002);
  EXPECT_EQ(movers[0].kind, MoverKind::kTrajectory);
  EXPECT_NEAR(movers[0].trajectory[1].t_s, 0.4, 1e-12);
  // (2, 0) rotated by 90 degrees = (0, 2), plus the offset.
  EXPECT_NEAR(movers[0].trajectory[1].x_m, 100.0, 1e-12);
  EXPECT_NEAR(movers[0].trajectory[1].y_m, 52.0, 1e-12);
  spec.max_people = 1;
  ASSERT_EQ(MoversFromRecordedTracks(tracks, spec).size(), 1u);
  EXPECT_EQ(MoversFromRecordedTracks(tracks, spec)[0].id, 1005);
}

}  // namespace
}  // namespace slammtt
