// Time between two utimes (int64 microseconds), for algorithm code that takes utimes from
// outside. Header-only and pure, like common/angle.h.
//
// Why not `1e-6 * (later - earlier)`: the int64 subtraction overflows (undefined behaviour)
// when the two lie more than 2^63 us apart, which a corrupted or hostile message can make
// happen. Converting each first is exact for |utime| < 2^53 us (285 years), so for every real
// utime the result is bit for bit the old expression's; beyond, it is rounded, never undefined.
#pragma once

#include <cstdint>

namespace slammtt {

// later - earlier in microseconds, as a double.
inline double MicrosecondsBetween(int64_t later_utime, int64_t earlier_utime) {
  return static_cast<double>(later_utime) - static_cast<double>(earlier_utime);
}

// later - earlier in seconds.
inline double SecondsBetween(int64_t later_utime, int64_t earlier_utime) {
  return 1e-6 * MicrosecondsBetween(later_utime, earlier_utime);
}

}  // namespace slammtt
