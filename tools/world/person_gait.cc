#include "tools/world/person_gait.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace slammtt {

GaitSpec GaitFromLegs(const LegSpec& legs) {
  GaitSpec gait;
  gait.leg_radius_m = legs.radius_m;
  gait.hip_width_m = legs.hip_width_m;
  gait.sway_m = legs.sway_m;
  return gait;
}

double CadenceHz(const GaitSpec& gait, double speed_mps) {
  if (!(speed_mps >= gait.standing_speed_mps)) return gait.min_cadence_hz;
  // C [steps/min] = sqrt(60 v / W); in steps per second C / 60 = sqrt(v / (60 W)).
  double cadence = std::max(gait.min_cadence_hz,
                            std::sqrt(speed_mps / (60.0 * gait.walk_ratio_m_per_spm)));
  if (speed_mps / cadence > gait.max_step_m) cadence = speed_mps / gait.max_step_m;
  return cadence;
}

double StepLengthM(const GaitSpec& gait, double speed_mps) {
  if (!(speed_mps >= gait.standing_speed_mps)) return 0.0;
  return speed_mps / CadenceHz(gait, speed_mps);
}

PersonGait::PersonGait(const GaitSpec& gait, double sway_phase_rad)
    : gait_(gait), sway_phase_rad_(sway_phase_rad) {}

void PersonGait::Target(const MoverState& body, double speed, int leg, double* x,
                        double* y) const {
  const double step_m = StepLengthM(gait_, speed);
  const double side_m = (leg == 0 ? 0.5 : -0.5) * gait_.hip_width_m;
  const double hx = std::cos(heading_rad_);
  const double hy = std::sin(heading_rad_);
  // A step reaches at most kLongestStep step lengths past the standing foot (along the
  // heading): starting from standing, the feet catch up with their lead of half a step over a
  // few steps instead of making one giant first step.
  constexpr double kLongestStep = 1.2;
  const Foot& other = foot_[static_cast<size_t>(1 - leg)];
  const double from_other_m = (body.x_m - other.x_m) * hx + (body.y_m - other.y_m) * hy;
  const double ahead_m = std::min(0.5 * step_m, kLongestStep * step_m - from_other_m);
  *x = body.x_m + hx * ahead_m - hy * side_m;
  *y = body.y_m + hy * ahead_m + hx * side_m;
}

void PersonGait::Update(double t_s, const MoverState& body) {
  const double speed = std::hypot(body.vx_mps, body.vy_mps);
  const bool standing = !(speed >= gait_.standing_speed_mps);
  if (!standing) heading_rad_ = std::atan2(body.vy_mps, body.vx_mps);
  const double cadence = CadenceHz(gait_, speed);
  if (!started_) {
    started_ = true;
    time_s_ = t_s;
    phase_ = 0.0;
    for (int leg = 0; leg < 2; ++leg) {
      const double side_m = (leg == 0 ? 0.5 : -0.5) * gait_.hip_width_m;
      foot_[static_cast<size_t>(leg)] = Foot{body.x_m - std::sin(heading_rad_) * side_m,
                                             body.y_m + std::cos(heading_rad_) * side_m};
    }
  }
  const double dt_s = std::max(0.0, t_s - time_s_);
  time_s_ = std::max(time_s_, t_s);
  const double new_phase = phase_ + cadence * dt_s;

  // Footfalls since the last call: each swinging leg lands where its step ends, at the body's
  // position then (moved back from now at the body's velocity; only the last two footfalls
  // matter when a long interval spans many steps).
  const int64_t old_step = static_cast<int64_t>(std::floor(phase_));
  const int64_t new_step = static_cast<int64_t>(std::floor(new_phase));
  for (int64_t k = std::max(old_step, new_step - 2); k < new_step; ++k) {
    const int leg = static_cast<int>(k % 2);
    const double since_landing_s = (new_phase - static_cast<double>(k + 1)) / cadence;
    const MoverState then{body.x_m - body.vx_mps * since_landing_s,
                          body.y_m - body.vy_mps * since_landing_s, body.vx_mps, body.vy_mps};
    Target(then, speed, leg, &foot_[static_cast<size_t>(leg)].x_m,
           &foot_[static_cast<size_t>(leg)].y_m);
  }
  phase_ = new_phase;

  const int swinging = static_cast<int>(new_step % 2);
  const double in_step = phase_ - static_cast<double>(new_step);
  const double support = 1.0 - gait_.swing_fraction;
  for (int leg = 0; leg < 2; ++leg) {
    const Foot& foot = foot_[static_cast<size_t>(leg)];
    LegState& state = legs_[static_cast<size_t>(leg)];
    state = LegState{foot.x_m, foot.y_m, 0.0, 0.0, true};
    if (leg != swinging || in_step < support) continue;
    const double u = (in_step - support) / gait_.swing_fraction;
    double tx = 0.0;
    double ty = 0.0;
    Target(body, speed, leg, &tx, &ty);
    // The target moves with the body, so d/dt of foot + (target - foot) s adds s * v_body.
    const double s = u * u * (3.0 - 2.0 * u);
    const double ds_dt = 6.0 * u * (1.0 - u) * cadence / gait_.swing_fraction;
    state.stance = false;
    state.x_m = foot.x_m + (tx - foot.x_m) * s;
    state.y_m = foot.y_m + (ty - foot.y_m) * s;
    state.vx_mps = (tx - foot.x_m) * ds_dt + s * body.vx_mps;
    state.vy_mps = (ty - foot.y_m) * ds_dt + s * body.vy_mps;
  }
  if (standing && gait_.sway_m > 0.0) {
    const double w = 2.0 * M_PI * gait_.sway_hz;
    const double offset = gait_.sway_m * std::sin(w * t_s + sway_phase_rad_);
    const double rate = gait_.sway_m * w * std::cos(w * t_s + sway_phase_rad_);
    const double nx = -std::sin(heading_rad_);
    const double ny = std::cos(heading_rad_);
    for (LegState& state : legs_) {
      state.x_m += nx * offset;
      state.y_m += ny * offset;
      state.vx_mps += nx * rate;
      state.vy_mps += ny * rate;
    }
  }
}

}  // namespace slammtt
