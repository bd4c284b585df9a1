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
// the angle minus a whole multiple of 2 * M_PI with no rounding, bit for bit what
// std::remainder(angle, 2 * M_PI) gives (an exact operation: C11 7.12.10.2, IEEE 754 remainder)
// with -M_PI moved to M_PI, a zero's sign included. Non-finite input (NaN, +-inf) is returned
// unchanged: callers check finiteness where outside data comes in, and a non-finite value stays
// visibly non-finite.
inline double WrapAngle(double angle_rad) {
  if (!std::isfinite(angle_rad)) return angle_rad;
  const double magnitude = std::abs(angle_rad);
  // Within [-pi, pi] the remainder is the angle itself (|x / 2pi| <= 1/2 rounds to 0, ties to
  // even): the common case of a small innovation needs no libm call.
  if (magnitude <= M_PI) return angle_rad <= -M_PI ? M_PI : angle_rad;
  // One turn off (|x| <= 3 pi; 3.0 * M_PI is exactly three times M_PI): the sum or difference
  // of two wrapped angles, or a scan given in [0, 2 pi) (half its beams), at the cost of a
  // subtraction instead of a libm call (about 10 ns: +21% CPU time of the segmenter on
  // 8000-beam scans). |x| - 2 pi is exact (Sterbenz: pi <= |x| <= 4 pi) and lies in (-pi, pi];
  // x's sign back gives remainder's result.
  if (magnitude <= 3.0 * M_PI) {
    const double wrapped = magnitude - 2.0 * M_PI;
    if (angle_rad > 0.0) return wrapped;
    return wrapped >= M_PI ? M_PI : -wrapped;  // -3 pi wraps to pi, not -pi
  }
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);  // in [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

}  // namespace slammtt
