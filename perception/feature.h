// A point feature (a compact object: a post, a bin, a chair leg, a person's leg; never a wall)
// made from one cluster of a scan (paper section 3, Algorithm 1, steps 8-9), in
// the sensor frame: x forward, y left, bearings CCW from x in (-pi, pi].
#pragma once

#include <Eigen/Core>

#include <cstdint>

namespace slammtt {

struct Feature {
  double range_m = 0.0;      // range of the centre (SegmenterOptions::centre_rule) from the sensor
  double bearing_rad = 0.0;  // bearing of the centre, (-pi, pi]
  double width_m = 0.0;      // distance between the cluster's first and last point
  int num_points = 0;        // beams in the cluster
  // Estimated object radius behind the centre (0 for CentreRule::kMiddlePoint, whose centre is
  // on the outline). Not in feature_t; kept for tests and diagnostics.
  double radius_m = 0.0;
  // Measurement covariance of (range_m, bearing_rad) (paper eq. 14, R): [m^2, m rad; m rad,
  // rad^2]. Always symmetric positive definite.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  // How much the cluster looks like a person's leg, in [0, 1] (leg_likeness.h).
  double leg_likeness = 0.0;
  // Input indices (positions in the scan as given) of the first and last beam of the cluster in
  // CCW order. For a cluster across a 360-degree scan's seam, last_beam_index may be smaller.
  int32_t first_beam_index = -1;
  int32_t last_beam_index = -1;
  // Index of this cluster in Segmenter::leg_clusters() (its leg features and centroid).
  int32_t leg_cluster = -1;
  // Edges of the cluster (0, 1 or 2) whose neighbouring beam had a usable return (farther: the
  // object ends there; nearer: something hides it). Next to a beam without one (no echo, a
  // dropout at grazing incidence, a dark or glass surface) the object may go on unseen.
  // Not in feature_t.
  int bounded_edges = 0;
};

}  // namespace slammtt
