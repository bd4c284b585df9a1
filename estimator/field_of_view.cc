#include "estimator/field_of_view.h"

#include <algorithm>

#include "common/angle.h"

namespace slammtt {

bool FieldOfView::ContainsWithMargin(double bearing_rad, double margin_rad) const {
  if (full()) return true;
  if (symmetric) return std::abs(bearing_rad) + margin_rad <= end_rad;
  // Where the bearing lies CCW from the start, in [0, 2 pi).
  double from_start = WrapAngle(bearing_rad - start_rad);
  if (from_start < 0.0) from_start += 2.0 * M_PI;
  const double width = end_rad - start_rad;
  return from_start - margin_rad >= 0.0 && from_start + margin_rad <= width;
}

}  // namespace slammtt
