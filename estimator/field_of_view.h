// The laser's field of view in the sensor frame (x forward, y left, bearings CCW): the bearings
// from start_rad counter-clockwise to end_rad, not necessarily symmetric about the sensor's
// heading (a laser partly blocked by the robot's body, or a scanner whose view is [-120, 90]
// degrees). EstimatorOptions gives it as field_of_view_deg, centred on the heading, or as
// field_of_view_start_deg / field_of_view_end_deg (estimator_options.h: FieldOfViewOf).
//
// A symmetric view is judged with the very expressions the estimator always used
// (|bearing| against half the width), so that the outputs of every configuration without a
// start and an end stay byte for byte what they were.
#pragma once

#include <cmath>

namespace slammtt {

struct FieldOfView {
  double start_rad = -M_PI;
  double end_rad = M_PI;      // start_rad < end_rad <= start_rad + 2 pi
  bool symmetric = true;      // start_rad = -end_rad

  bool full() const { return end_rad - start_rad >= 2.0 * M_PI; }
  // Whether the bearing (wrapped to (-pi, pi]) lies inside the view with at least margin_rad
  // to spare from both edges (margin 0: inside or on an edge).
  bool ContainsWithMargin(double bearing_rad, double margin_rad) const;
  // Outside the view (on an edge counts as inside).
  bool Excludes(double bearing_rad) const { return !ContainsWithMargin(bearing_rad, 0.0); }
};

}  // namespace slammtt
