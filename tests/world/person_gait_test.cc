// The walking gait (person_gait.h): stance feet stand still, legs keep up with the body, the
// cadence and step length follow the published walk ratio, the feet stay a plausible stride
// apart, and a standing person's feet stand side by side.
#include "tools/world/person_gait.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tools/world/mover_path.h"

namespace slammtt {
namespace {

// Straight walk along x at `speed` from the origin.
MoverState Straight(double t_s, double speed) { return MoverState{speed * t_s, 0.0, speed, 0.0}; }

TEST(PersonGaitTest, CadenceAndStepLengthFollowTheWalkRatio) {
  const GaitSpec gait;
  // Issue 11 / gait literature: about 1.7-2 steps/s at 1-1.5 m/s; at 1.3 m/s:
  // sqrt(1.3 / (60 * 0.006)) = 1.900 Hz, step 0.684 m.
  EXPECT_NEAR(CadenceHz(gait, 1.3), 1.9003, 1e-4);
  EXPECT_GE(CadenceHz(gait, 1.3), 1.7);
  EXPECT_LE(CadenceHz(gait, 1.3), 2.0);
  EXPECT_NEAR(StepLengthM(gait, 1.3), 1.3 / 1.9003, 1e-4);
  EXPECT_LT(CadenceHz(gait, 1.0), CadenceHz(gait, 1.5));
  EXPECT_GT(StepLengthM(gait, 1.5), StepLengthM(gait, 1.0));
  EXPECT_EQ(StepLengthM(gait, 0.0), 0.0);
  EXPECT_LE(StepLengthM(gait, 10.0), gait.max_step_m + 1e-12);
}

TEST(PersonGaitTest, MeasuredCadenceAt1p3MpsIsInThePublishedRange) {
  PersonGait person(GaitSpec{});
  int landings = 0;
  bool was_swinging[2] = {false, false};
  const double dt = 0.01;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * dt;
    person.Update(t, Straight(t, 1.3));
    for (int leg = 0; leg < 2; ++leg) {
      const bool swinging = !person.legs()[static_cast<size_t>(leg)].stance;
      if (was_swinging[leg] && !swinging) ++landings;
      was_swinging[leg] = swinging;
    }
  }
  const double cadence_hz = landings / 20.0;
  EXPECT_GE(cadence_hz, 1.7);
  EXPECT_LE(cadence_hz, 2.0);
}

TEST(PersonGaitTest, StanceFootDoesNotMoveAndLegsMoveInBursts) {
  PersonGait person(GaitSpec{});
  LegState previous[2];
  int stance_samples[2] = {0, 0};
  int samples = 0;
  const double dt = 0.01;
  for (int i = 0; i <= 3000; ++i) {
    const double t = i * dt;
    person.Update(t, Straight(t, 1.3));
    for (size_t leg = 0; leg < 2; ++leg) {
      const LegState& now = person.legs()[leg];
      if (now.stance) {
        EXPECT_EQ(now.vx_mps, 0.0);
        EXPECT_EQ(now.vy_mps, 0.0);
        ++stance_samples[leg];
        if (i > 0 && previous[leg].stance) {
          ASSERT_EQ(now.x_m, previous[leg].x_m) << "t " << t;
          ASSERT_EQ(now.y_m, previous[leg].y_m) << "t " << t;
        }
      }
      previous[leg] = now;
    }
    ++samples;
  }
  // Each leg swings 40 % of its cycle (swing_fraction 0.8 of every other step).
  for (int leg = 0; leg < 2; ++leg) {
    EXPECT_NEAR(static_cast<double>(stance_samples[leg]) / samples, 0.6, 0.02);
  }
}

TEST(PersonGaitTest, MeanLegVelocityEqualsTheBodyVelocity) {
  for (double speed : {0.6, 1.0, 1.3, 1.6}) {
    SCOPED_TRACE(speed);
    PersonGait person(GaitSpec{});
    const double dt = 0.01;
    double sum_vx[2] = {0.0, 0.0};
    double sum_vy[2] = {0.0, 0.0};
    double start_x[2] = {0.0, 0.0};
    int n = 0;
    for (int i = 0; i <= 6000; ++i) {
      const double t = i * dt;
      person.Update(t, Straight(t, speed));
      if (t < 5.0) continue;  // after the feet caught up with their lead
      for (size_t leg = 0; leg < 2; ++leg) {
        if (n == 0) start_x[leg] = person.legs()[leg].x_m;
        sum_vx[leg] += person.legs()[leg].vx_mps;
        sum_vy[leg] += person.legs()[leg].vy_mps;
      }
      ++n;
    }
    for (size_t leg = 0; leg < 2; ++leg) {
      // Mean of the reported velocities over 55 s, and the displacement over that time (a foot
      // is at most 0.7 steps behind and 0.5 ahead of the body: within 1.2 steps of its
      // displacement).
      EXPECT_NEAR(sum_vx[leg] / n, speed, 0.02 * speed);
      EXPECT_NEAR(sum_vy[leg] / n, 0.0, 1e-9);
      const double displacement = person.legs()[leg].x_m - start_x[leg];
      EXPECT_NEAR(displacement / 55.0, speed, 1.2 * StepLengthM(GaitSpec{}, speed) / 55.0);
    }
  }
}

TEST(PersonGaitTest, FeetNeverFartherApartThanAPlausibleStrideAlsoRoundCorners) {
  // A walk round a 4 x 3 m rectangle at 1.4 m/s with 2 s stops at two corners.
  MoverSpec spec;
  spec.kind = MoverKind::kWaypoints;
  spec.speed_mps = 1.4;
  spec.waypoints = {{0, 0, 0}, {4, 0, 2}, {4, 3, 0}, {0, 3, 2}, {0, 0, 0}};
  std::mt19937_64 rng(1);
  const MoverPath path = BuildMoverPath(spec, 60.0, rng);
  PersonGait person(GaitSpec{});
  double widest = 0.0;
  double farthest_from_body = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i * 0.01;
    const MoverState body = path.StateAt(t);
    person.Update(t, body);
    const auto& legs = person.legs();
    widest = std::max(widest, std::hypot(legs[0].x_m - legs[1].x_m, legs[0].y_m - legs[1].y_m));
    for (const LegState& leg : legs) {
      farthest_from_body =
          std::max(farthest_from_body, std::hypot(leg.x_m - body.x_m, leg.y_m - body.y_m));
    }
  }
  // Step 0.70 m at 1.4 m/s, hip 0.2 m: sqrt(0.70^2 + 0.2^2) = 0.73 m between landed feet in
  // steady walking; a step is at most 1.2 step lengths (0.84 m) while the feet catch up
  // after a start from standing: sqrt(0.84^2 + 0.2^2) = 0.87 m.
  EXPECT_LE(widest, 0.9);
  EXPECT_GE(widest, 0.7);
  EXPECT_LE(farthest_from_body, 0.9);
}

TEST(PersonGaitTest, StandingFeetStandSideBySideAndSwayALittle) {
  GaitSpec gait;
  PersonGait person(gait, 0.3);
  for (int i = 0; i <= 500; ++i) {
    const double t = i * 0.01;
    person.Update(t, Straight(t, 1.2));
  }
  const double stop_x = 1.2 * 5.0;
  double max_offset = 0.0;
  for (int i = 1; i <= 1000; ++i) {
    const double t = 5.0 + i * 0.01;
    person.Update(t, MoverState{stop_x, 0.0, 0.0, 0.0});
    if (t < 7.5) continue;  // two steps at min_cadence_hz bring the feet together
    const auto& legs = person.legs();
    EXPECT_NEAR(legs[0].x_m, stop_x, 1e-9);
    EXPECT_NEAR(legs[1].x_m, stop_x, 1e-9);
    EXPECT_NEAR(legs[0].y_m - legs[1].y_m, gait.hip_width_m, 1e-9);  // left is +y
    max_offset = std::max(max_offset, std::abs(0.5 * (legs[0].y_m + legs[1].y_m)));
  }
  EXPECT_GT(max_offset, 0.5 * gait.sway_m);
  EXPECT_LE(max_offset, gait.sway_m + 1e-12);
}

TEST(PersonGaitTest, SameMotionSameTimesSameBits) {
  PersonGait a(GaitSpec{}, 1.0);
  PersonGait b(GaitSpec{}, 1.0);
  for (int i = 0; i <= 300; ++i) {
    const double t = i * 0.1;
    a.Update(t, Straight(t, 1.1));
    b.Update(t, Straight(t, 1.1));
    ASSERT_EQ(a.legs()[0].x_m, b.legs()[0].x_m);
    ASSERT_EQ(a.legs()[1].y_m, b.legs()[1].y_m);
  }
}

}  // namespace
}  // namespace slammtt
