// Where a moving object is at any time: every mover kind of the scenario (constant velocity,
// waypoints, recorded trajectory, random walk) becomes one piecewise-linear timed path, so the
// world asks every mover the same question and gets exact positions and velocities at any time,
// whatever the scan and odometry rates.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "tools/world/scenario.h"

namespace slammtt {

// State of a mover at one moment.
struct MoverState {
  double x_m = 0.0;
  double y_m = 0.0;
  double vx_mps = 0.0;
  double vy_mps = 0.0;
};

// Linear interpolation between knots of strictly increasing time; before the first knot the
// object stands at it, after the last one at the last one (velocity zero), unless the path is a
// loop: then the knots from `repeat_from_s` to the last one form a closed lap that repeats
// forever (time folded into the lap with fmod, which is exact), so a looping mover costs one
// lap of knots however short the lap and however long the run. The object exists in
// [appear_s, disappear_s).
class MoverPath {
 public:
  MoverPath() = default;
  // `knots` non-empty with strictly increasing t_s; `repeat_from_s`, when given, the time of a
  // knot before the last one at the last knot's position. CHECK-style std::invalid_argument
  // otherwise (a programming error: scenarios are validated before paths are built).
  MoverPath(std::vector<TimedPoint> knots, double appear_s, double disappear_s,
            std::optional<double> repeat_from_s = std::nullopt);

  bool ExistsAt(double t_s) const { return t_s >= appear_s_ && t_s < disappear_s_; }
  // Position and velocity at t_s (also outside the existence interval: the clamped path).
  // Exactly at a knot the velocity is that of the segment that starts there.
  MoverState StateAt(double t_s) const;

  const std::vector<TimedPoint>& knots() const { return knots_; }
  // Start of the repeated lap of a loop; nullopt for a path that ends at its last knot.
  const std::optional<double>& repeat_from_s() const { return repeat_from_s_; }

 private:
  std::vector<TimedPoint> knots_;
  double appear_s_ = 0.0;
  double disappear_s_ = std::numeric_limits<double>::infinity();
  std::optional<double> repeat_from_s_;
};

// The path of a mover of the scenario over [0, horizon_s] (a waypoint loop: for ever, one lap of
// knots). Random walks draw their legs from `rng` (the caller seeds it per object); the other
// kinds draw nothing. The spec must be free of FindScenarioProblems() problems.
MoverPath BuildMoverPath(const MoverSpec& spec, double horizon_s, std::mt19937_64& rng);

}  // namespace slammtt
