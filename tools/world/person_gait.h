// A walking person's two legs from the motion of the body: one leg stands (stance: it does not
// move) while the other swings forward to its next footfall, step length and cadence follow the
// walking speed, and a standing person's feet stand side by side with a little sway.
//
// Cadence and step length (published gait figures): the walk ratio W = step length / cadence is
// nearly constant over ordinary walking speeds, about 0.006 m per (step/min) in healthy adults
// (the walk ratio of Sekiya and Nagasaki; Murakami and Otaka, J. Phys. Ther. Sci. 2017,
// PMC5430280: constancy holds above about 62 m/min = 1.03 m/s). With speed v = L * C / 60 and
// L = W * C this gives
//   cadence C = sqrt(60 v / W) steps/min, step length L = v * 60 / C,
// e.g. 1.67 Hz (100 steps/min) and 0.60 m at 1.0 m/s, 1.90 Hz and 0.68 m at 1.3 m/s, 2.04 Hz and
// 0.73 m at 1.5 m/s. Below min_cadence_hz (slow walking, where the ratio is no longer constant)
// the cadence stays at min_cadence_hz and steps get shorter; a step is at most max_step_m long
// (faster "walkers" step faster instead).
//
// Phases: step k spans gait phase [k, k + 1) (phase advances at the cadence); leg k % 2 swings
// during the last swing_fraction of the step and lands at phase k + 1; the other leg stands. Both
// stand during the first 1 - swing_fraction of each step (double support; with the default 0.8 a
// leg swings 40 % of its cycle, as in ordinary walking). A leg lands half a step ahead of the
// body's position at that moment and hip_width / 2 to its side of the heading; the swing foot moves
// from its lift-off point towards that point (which moves with the body) along a smooth-step
// profile, so it never overshoots where a stopping or turning body will be. So each leg advances
// one stride (two steps) per cycle: over whole cycles a leg moves with the body's mean velocity.
// Heading: the direction of motion (kept while the person stands). A step reaches at most 1.2
// step lengths past the standing foot, so after a start from standing the feet catch up with
// their half-step lead over a few steps instead of one giant first step.
//
// Standing (speed below standing_speed_mps): steps continue at min_cadence_hz with length 0, so
// within two steps the feet stand side by side at +-hip_width / 2 and then stand still, apart
// from a sway of both feet across the heading of amplitude sway_m at sway_hz.
//
// Update() is called with non-decreasing times (the world calls it at every scan time); the
// phase integrates the cadence at the body's speed at each call, so the legs of the same body
// motion sampled at the same times are the same bits.
#pragma once

#include <array>

#include "tools/world/mover_path.h"
#include "tools/world/scenario.h"

namespace slammtt {

struct GaitSpec {
  double leg_radius_m = 0.06;
  double hip_width_m = 0.2;          // between the leg centres, across the heading
  double walk_ratio_m_per_spm = 0.006;  // step length / cadence (m per step/min)
  double min_cadence_hz = 1.0;       // steps per second at slow speeds and while standing
  double max_step_m = 1.0;
  double swing_fraction = 0.8;       // share of a step in which the swinging leg moves
  double standing_speed_mps = 0.05;
  double sway_m = 0.01;
  double sway_hz = 0.25;
};

// The gait of a LegSpec (hip width, leg radius, sway).
GaitSpec GaitFromLegs(const LegSpec& legs);

// Steps per second at walking speed `speed_mps` (>= 0).
double CadenceHz(const GaitSpec& gait, double speed_mps);
// Step length at that speed: speed / cadence (0 below standing_speed_mps).
double StepLengthM(const GaitSpec& gait, double speed_mps);

struct LegState {
  double x_m = 0.0;
  double y_m = 0.0;
  double vx_mps = 0.0;
  double vy_mps = 0.0;
  bool stance = true;  // planted (not swinging)
};

class PersonGait {
 public:
  // `sway_phase_rad`: phase of the standing sway (people do not sway in step).
  explicit PersonGait(const GaitSpec& gait, double sway_phase_rad = 0.0);

  // Moves the legs to time t_s for the body's state then. The first call (and the first after
  // Reset) puts the feet side by side at the body, both standing.
  void Update(double t_s, const MoverState& body);
  void Reset() { started_ = false; }

  // Leg 0 is the left leg (left of the heading), leg 1 the right one.
  const std::array<LegState, 2>& legs() const { return legs_; }
  double phase() const { return phase_; }
  double heading_rad() const { return heading_rad_; }

 private:
  struct Foot {
    double x_m = 0.0;  // planted position (stance) or lift-off position (swing)
    double y_m = 0.0;
  };
  // Where leg `leg` lands for this body state: half a step ahead, half the hip width aside.
  void Target(const MoverState& body, double speed, int leg, double* x, double* y) const;

  GaitSpec gait_;
  double sway_phase_rad_ = 0.0;
  bool started_ = false;
  double time_s_ = 0.0;
  double phase_ = 0.0;
  double heading_rad_ = 0.0;
  std::array<Foot, 2> foot_{};
  std::array<LegState, 2> legs_{};
};

}  // namespace slammtt
