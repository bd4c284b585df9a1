#include "tools/world/mover_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/world/portable_random.h"

namespace slammtt {

MoverPath::MoverPath(std::vector<TimedPoint> knots, double appear_s, double disappear_s,
                     std::optional<double> repeat_from_s)
    : knots_(std::move(knots)),
      appear_s_(appear_s),
      disappear_s_(disappear_s),
      repeat_from_s_(repeat_from_s) {
  if (knots_.empty()) throw std::invalid_argument("MoverPath: no knots");
  for (size_t i = 1; i < knots_.size(); ++i) {
    if (!(knots_[i].t_s > knots_[i - 1].t_s)) {
      throw std::invalid_argument("MoverPath: knot times must increase strictly");
    }
  }
  if (repeat_from_s_) {
    const TimedPoint& last = knots_.back();
    const auto start = std::find_if(knots_.begin(), knots_.end(), [&](const TimedPoint& k) {
      return k.t_s == *repeat_from_s_;
    });
    if (start == knots_.end() || !(start->t_s < last.t_s) || start->x_m != last.x_m ||
        start->y_m != last.y_m) {
      throw std::invalid_argument("MoverPath: a loop must start at a knot where the path ends");
    }
  }
}

MoverState MoverPath::StateAt(double t_s) const {
  MoverState state;
  if (knots_.empty()) return state;
  if (repeat_from_s_ && t_s >= knots_.back().t_s) {
    // Into the lap [repeat_from_s, last knot): fmod is exact, so every lap is the same.
    t_s = *repeat_from_s_ + std::fmod(t_s - *repeat_from_s_, knots_.back().t_s - *repeat_from_s_);
  }
  if (t_s < knots_.front().t_s || knots_.size() == 1) {
    state.x_m = knots_.front().x_m;
    state.y_m = knots_.front().y_m;
    return state;
  }
  if (t_s >= knots_.back().t_s) {
    state.x_m = knots_.back().x_m;
    state.y_m = knots_.back().y_m;
    return state;
  }
  // First knot strictly after t_s; the segment starts at the knot before it.
  const auto after = std::upper_bound(knots_.begin(), knots_.end(), t_s,
                                      [](double t, const TimedPoint& k) { return t < k.t_s; });
  const TimedPoint& a = *(after - 1);
  const TimedPoint& b = *after;
  const double dt = b.t_s - a.t_s;
  state.vx_mps = (b.x_m - a.x_m) / dt;
  state.vy_mps = (b.y_m - a.y_m) / dt;
  state.x_m = a.x_m + state.vx_mps * (t_s - a.t_s);
  state.y_m = a.y_m + state.vy_mps * (t_s - a.t_s);
  return state;
}

namespace {

// Paths are built a little past the horizon so that the velocity at the last event is the
// path's, not the "stopped after the last knot" zero.
constexpr double kHorizonMarginS = 1.0;

void AppendKnot(std::vector<TimedPoint>* knots, double t_s, double x_m, double y_m) {
  if (!knots->empty() && !(t_s > knots->back().t_s)) return;  // nothing new happened
  knots->push_back(TimedPoint{t_s, x_m, y_m});
}

MoverPath ConstantVelocityPath(const MoverSpec& spec, double horizon_s) {
  std::vector<TimedPoint> knots;
  AppendKnot(&knots, spec.appear_s, spec.start_x_m, spec.start_y_m);
  const double end_s = std::min(spec.disappear_s, horizon_s + kHorizonMarginS);
  if (end_s > spec.appear_s) {
    const double dt = end_s - spec.appear_s;
    AppendKnot(&knots, end_s, spec.start_x_m + spec.vx_mps * dt, spec.start_y_m + spec.vy_mps * dt);
  }
  return MoverPath(std::move(knots), spec.appear_s, spec.disappear_s);
}

// Every waypoint once (stay, leave), or one lap back to the first waypoint and its wait (loop):
// the number of knots is bounded by the number of waypoints, never by the run's length.
MoverPath WaypointPath(const MoverSpec& spec) {
  std::vector<TimedPoint> knots;
  const std::vector<MoverWaypoint>& wps = spec.waypoints;
  double t = spec.appear_s;
  double x = wps.front().x_m;
  double y = wps.front().y_m;
  AppendKnot(&knots, t, x, y);
  t += wps.front().wait_s;
  AppendKnot(&knots, t, x, y);
  const double lap_start_s = knots.back().t_s;
  const bool loop = spec.at_end == PathEnd::kLoop;
  for (size_t i = 1; i <= wps.size(); ++i) {
    if (i == wps.size() && !loop) break;
    const MoverWaypoint& wp = wps[i % wps.size()];  // the loop closes at the first waypoint
    t += std::hypot(wp.x_m - x, wp.y_m - y) / spec.speed_mps;
    x = wp.x_m;
    y = wp.y_m;
    AppendKnot(&knots, t, x, y);
    t += wp.wait_s;
    AppendKnot(&knots, t, x, y);
  }
  if (loop) {
    // The lap ends where it started. (Only when the closing walk takes less time than the
    // resolution of t does the last knot stand elsewhere: it moves by less than speed * ulp(t).)
    knots.back().x_m = wps.front().x_m;
    knots.back().y_m = wps.front().y_m;
  }
  double disappear_s = spec.disappear_s;
  if (spec.at_end == PathEnd::kLeave) {
    disappear_s = std::min(disappear_s, t);  // leaves on reaching its last waypoint (and wait)
    if (!(disappear_s > spec.appear_s)) disappear_s = spec.appear_s;
  }
  // A lap that takes no time (every waypoint at one place, no wait) is a mover standing still.
  std::optional<double> repeat_from_s;
  if (loop && knots.back().t_s > lap_start_s) repeat_from_s = lap_start_s;
  return MoverPath(std::move(knots), spec.appear_s, disappear_s, repeat_from_s);
}

MoverPath TrajectoryPath(const MoverSpec& spec) {
  const double first_s = spec.trajectory.front().t_s;
  const double last_s = spec.trajectory.back().t_s;
  // Exists from the first to the last sample, both included.
  const double appear_s = std::max(spec.appear_s, first_s);
  const double disappear_s =
      std::min(spec.disappear_s, std::nextafter(last_s, std::numeric_limits<double>::infinity()));
  return MoverPath(spec.trajectory, appear_s, disappear_s);
}

MoverPath RandomWalkPath(const MoverSpec& spec, double horizon_s, std::mt19937_64& rng) {
  const RandomWalkSpec& w = spec.random_walk;
  const double stop_s = std::min(spec.disappear_s, horizon_s + kHorizonMarginS);
  std::vector<TimedPoint> knots;
  double t = spec.appear_s;
  double x = spec.start_x_m;
  double y = spec.start_y_m;
  double heading = w.heading_rad;
  AppendKnot(&knots, t, x, y);
  bool first_leg = true;
  while (t < stop_s) {
    // Fixed number of draws per leg (three, plus two for a redirected leg).
    const double duration_draw = UniformUnit(rng);
    const double reverse_draw = UniformUnit(rng);
    const double turn_draw = UniformUnit(rng);
    double duration = std::max(0.5, -w.mean_leg_s * std::log(1.0 - duration_draw));
    if (!first_leg) {
      if (reverse_draw < w.reverse_probability) {
        heading += M_PI;
      } else {
        heading += (2.0 * turn_draw - 1.0) * w.max_turn_rad;
      }
    }
    first_leg = false;
    heading = WrapAngle(heading);
    double end_x = x + spec.speed_mps * duration * std::cos(heading);
    double end_y = y + spec.speed_mps * duration * std::sin(heading);
    if (end_x < w.area_min_x_m || end_x > w.area_max_x_m || end_y < w.area_min_y_m ||
        end_y > w.area_max_y_m) {
      end_x = UniformBetween(rng, w.area_min_x_m, w.area_max_x_m);
      end_y = UniformBetween(rng, w.area_min_y_m, w.area_max_y_m);
      const double distance = std::hypot(end_x - x, end_y - y);
      if (distance < 1e-6) {
        // Already there (a tiny area): stand for the leg, so that time always advances.
        end_x = x;
        end_y = y;
      } else {
        heading = std::atan2(end_y - y, end_x - x);
        duration = distance / spec.speed_mps;
      }
    }
    t += duration;
    x = end_x;
    y = end_y;
    AppendKnot(&knots, t, x, y);
  }
  return MoverPath(std::move(knots), spec.appear_s, spec.disappear_s);
}

}  // namespace

MoverPath BuildMoverPath(const MoverSpec& spec, double horizon_s, std::mt19937_64& rng) {
  switch (spec.kind) {
    case MoverKind::kConstantVelocity:
      return ConstantVelocityPath(spec, horizon_s);
    case MoverKind::kWaypoints:
      return WaypointPath(spec);
    case MoverKind::kTrajectory:
      return TrajectoryPath(spec);
    case MoverKind::kRandomWalk:
      return RandomWalkPath(spec, horizon_s, rng);
  }
  throw std::invalid_argument("BuildMoverPath: unknown mover kind");
}

}  // namespace slammtt
