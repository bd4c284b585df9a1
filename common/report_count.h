// How often a repeated problem is reported: the 1st, 10th, 100th, ... occurrence. Header-only,
// so pure libraries (the drivers' device sessions) use the same rule as the programs
// (runtime/log.h includes it).
#pragma once

#include <cstdint>

namespace slammtt {

// True for the 1st, 10th, 100th, ... occurrence (count >= 1).
inline bool IsReportable(int64_t count) {
  if (count <= 0) return false;
  while (count % 10 == 0) count /= 10;
  return count == 1;
}

}  // namespace slammtt
