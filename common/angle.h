// Planar angles: the one WrapAngle of the project. Header-only and pure (standard library only),
// so every algorithm library may use it without linking anything (INTERFACE target
// slammtt_common, common/CMakeLists.txt).
//
// Headings and bearings are wrapped to (-pi, pi], the frame convention of docs/DEVELOPING.md.
// One definition matters beyond style: two different non-static functions `WrapAngle(double)`
// in namespace slammtt linked into one program break the one-definition rule, and which one a
// call reaches is then up to the linker.
#pragma once

#include <cmath>

namespace slammtt {

// Wraps an angle to (-pi, pi] (pi here is M_PI, the double nearest to pi). Exact: the result is
// the angle minus a whole multiple of 2 * M_PI with no rounding, because std::remainder is
// exact (C11 7.12.10.2, IEEE 754 remainder) and the one correction, -M_PI -> M_PI, adds 2 * M_PI
// to -M_PI exactly. Non-finite input (NaN, +-inf) is returned unchanged: callers check finiteness
// where outside data comes in, and a non-finite value stays visibly non-finite.
inline double WrapAngle(double angle_rad) {
  if (!std::isfinite(angle_rad)) return angle_rad;
  // Within [-pi, pi] the remainder is the angle itself (|x / 2pi| <= 1/2 rounds to 0, ties to
  // even): skip the libm call for the common case of a small innovation.
  if (std::abs(angle_rad) <= M_PI) return angle_rad <= -M_PI ? angle_rad + 2.0 * M_PI : angle_rad;
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);  // in [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

}  // namespace slammtt
