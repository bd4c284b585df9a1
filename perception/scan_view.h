// A read-only view of one laser scan, as the segmenter takes it: parallel per-beam arrays in the
// order the sensor produced them (laser_scan_t's layout), nothing copied. Angles are in the
// sensor frame (x forward, y left, CCW), any real value (they are wrapped to (-pi, pi] inside);
// they need not be sorted, evenly spaced or unique.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace slammtt {

struct ScanView {
  const float* angle_rad = nullptr;  // num_beams entries
  const float* range_m = nullptr;    // num_beams entries; ignored where valid[i] == 0
  const int8_t* valid = nullptr;     // num_beams entries, 0 = no return; nullptr = all valid
  size_t num_beams = 0;
  // The sensor's own limits (laser_scan_t::range_min_m / range_max_m). A non-finite or negative
  // value means "no limit from the sensor".
  double range_min_m = 0.0;
  double range_max_m = std::numeric_limits<double>::infinity();
};

// A view of vectors that outlive it. The arrays must have the same size (a caller's bug
// otherwise: the shortest size is used). `valid` may be empty (every beam valid).
inline ScanView MakeScanView(const std::vector<float>& angle_rad, const std::vector<float>& range_m,
                             const std::vector<int8_t>& valid = {}) {
  ScanView view;
  view.angle_rad = angle_rad.data();
  view.range_m = range_m.data();
  view.num_beams = angle_rad.size() < range_m.size() ? angle_rad.size() : range_m.size();
  if (!valid.empty()) {
    view.valid = valid.data();
    if (valid.size() < view.num_beams) view.num_beams = valid.size();
  }
  return view;
}

}  // namespace slammtt
