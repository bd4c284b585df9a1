// How much a compact cluster looks like a person's leg, from its shape alone: a hand-written,
// documented score in [0, 1], no learned model.
//
// The cues are three of the geometric features that Arras, Mozos and Burgard ("Using boosted
// features for the detection of people in 2D range data", ICRA 2007, Table I) found the most
// informative for legs: the width (their f6), the curvature or convexity towards the sensor
// (their f7 linearity / f8 circularity, here as the bulge of the points in front of the chord,
// which stays meaningful with three points) and the jump distances to the neighbouring
// segments (f4, f5: a leg stands in front of what is behind it). Leigh, Pineau, Olmedo and
// Zhang ("Person tracking and following with 2D laser scanners", ICRA 2015) use the same
// family of features. Each cue becomes a factor in [0, 1]:
//
//  - width: the object's diameter is not the first-to-last distance: each true edge lies
//    between the edge beam and the next beam, which missed, so the diameter is somewhere in
//    [r extent, r (extent + 2 spacing)] (r the cluster's mean range). The factor is the mean,
//    over that interval, of a trapezoid that is 1 on [min_diameter_m, max_diameter_m]
//    and falls linearly to 0 over diameter_margin_m below and 3 diameter_margin_m above
//    (two legs side by side or overlapping make one wider cluster). At 0.35 degrees and 2 m the
//    interval is 2.4 cm long and the factor sharp; at 0.9 degrees and 4 m (a leg is one or two
//    beams) it is 13 cm long and the factor says "possibly": the rule follows range and beam
//    spacing, never the sensor's name.
//  - convexity: c = bulge / (d / 2), with bulge the mean distance of the middle half of the
//    points in front of the chord between the end points (towards the sensor) and d the
//    nominal diameter r (extent + spacing). A half circle gives c of about 0.7, a flat board 0,
//    a concave corner below 0. With sigma_c the standard deviation of c that range noise alone
//    gives (sigma_r^2 / k for the k middle points plus sigma_r^2 / 2 for the chord), the factor
//    is 0.2 + 0.8 Phi((c - 0.2) / sqrt(sigma_c^2 + 0.1^2)): a clean arc scores 1, a clean flat
//    board about 0.2 (with sigma_r 0.03 m, a 0.15 m board about 0.4), a noisy short cluster
//    about 0.6; a cluster of two points has no curvature, 0.7. A cluster wider than one leg
//    (nominal diameter above 0.18 m) may be two legs side by side, whose notch between them
//    is not evidence against a person: its factor is at least 0.6.
//  - edges: an edge where the adjacent beam is nearer (another object hides this one) is not
//    the object's own outline: 1 with no such edge, 0.85 with one, 0.5 with both (a piece of
//    background seen between two nearer objects).
// The score is the product of the three.
#pragma once

#include <cstddef>

#include "perception/centre_estimation.h"

namespace slammtt {

struct LegLikenessOptions {
  // Diameters of a leg at the laser's height (calf to knee, trousers): the score's width factor
  // is 1 between these. People's legs are about 0.1-0.15 m across; chair and table legs
  // 0.03-0.06 m, which the factor rejects where the beam spacing allows.
  double min_diameter_m = 0.08;
  double max_diameter_m = 0.3;
  // The factor falls to 0 over this margin below the minimum and three times it above the
  // maximum.
  double diameter_margin_m = 0.03;
  // The convexity factor's value for a clearly flat or concave cluster (b below): how much the
  // shape may count against the width.
  double convexity_floor = 0.6;
};

// Shape cues of one cluster (points as ClusterView gives them, count >= 1).
struct ClusterShape {
  double mean_range_m = 0.0;
  double extent_rad = 0.0;      // last minus first bearing
  double spacing_rad = 0.0;     // mean angle between neighbouring beams (extent / (n - 1))
  double diameter_low_m = 0.0;  // the interval that holds the object's diameter
  double diameter_high_m = 0.0;
  double bulge_m = 0.0;         // middle points in front of the chord (0 for fewer than 3)
  size_t bulge_points = 0;      // how many points the bulge is the mean of
  size_t num_points = 0;
  bool first_edge_occluded = false;
  bool last_edge_occluded = false;
};

// spacing_rad is the scan's beam spacing near the cluster, used when the cluster has a single
// point (otherwise its own mean spacing is used).
ClusterShape DescribeClusterShape(const ClusterView& cluster, double spacing_rad);

// The score in [0, 1] (see above); sigma_r_m is one beam's range noise
// (SegmenterOptions::sigma_r_m). Non-finite cues give 0.
double LegLikeness(const ClusterShape& shape, const LegLikenessOptions& options,
                   double sigma_r_m);

}  // namespace slammtt
