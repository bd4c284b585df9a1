// Angle helpers shared by the estimator's models. Headings and bearings are wrapped to
// (-pi, pi], the project's frame convention (docs/DEVELOPING.md).
#pragma once

#include <cmath>

namespace slammtt {

// Wraps any finite angle to (-pi, pi]. Non-finite input is returned unchanged (callers reject
// it before it reaches a model).
inline double WrapAngle(double angle_rad) {
  if (!std::isfinite(angle_rad)) return angle_rad;
  // Within [-pi, pi] the remainder is the angle itself (|x / 2pi| <= 1/2 rounds to 0, ties to
  // even): skip the libm call for the common case of a small innovation.
  if (std::abs(angle_rad) <= M_PI) return angle_rad <= -M_PI ? angle_rad + 2.0 * M_PI : angle_rad;
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);  // in [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

inline double DegreesToRadians(double degrees) { return degrees * M_PI / 180.0; }
inline double RadiansToDegrees(double radians) { return radians * 180.0 / M_PI; }

}  // namespace slammtt
