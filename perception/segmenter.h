// Adaptive breakpoint segmentation of one laser scan into point features: the paper's
// Algorithm 1 (section 3) made safe for real scans.
//
// Per scan:
//  1. Beams are dropped, and counted, when flagged invalid (RPLIDAR reports distance 0 for no
//     return), when the angle or the range is NaN or infinite, or when the range is outside
//     [max(min_range_m, scan min), min(max_range_m, scan max)]. A dropped beam whose angle is
//     known stays in the ring as a marker until step 2 has counted the gap it leaves.
//  2. Angles are wrapped to (-pi, pi]. Beams in circular angle order (sorted, or sorted after a
//     rotation, as a revolution that starts anywhere) are used as they are; mostly clockwise
//     beams (the RPLIDAR's order in our CCW frame) are reversed first; what is still out of
//     order (RPLIDAR express mode swaps neighbours) is sorted by (angle, input index), a total
//     order, so the result does not depend on the algorithm (insertion sort from the wrap when
//     nearly sorted, std::sort otherwise). Then each usable beam records how many markers lie
//     between it and the previous usable beam (around the circle), and the markers go. Beams
//     within duplicate_angle_tolerance_rad of the previous one are one direction measured
//     twice: the nearer return is kept.
//  3. The breakpoint criterion (breakpoint_criterion.h, paper eq. 15) is evaluated between every
//     pair of angular neighbours, including the last and the first beam. On a 360-degree scan
//     that pair is one beam spacing apart and is tested like any other, so an object across the
//     seam is ONE cluster; on a 180-degree scan the pair is 180 degrees apart and always splits.
//     No scan-coverage flag is needed. If no pair splits, the points surround the sensor.
//     An invalid beam inside an object does not split it by itself: the criterion is applied
//     between its valid neighbours with their actual angular distance, which widens the
//     threshold. More than max_dropped_beams markers between two neighbours always split, and
//     so does a gap of more than max_beam_gap_rad (or lambda).
//  4. A cluster becomes a feature when it has at least min_points points, the distance between
//     its first and last point is at most max_width_m and it spans less than pi (a cluster that
//     surrounds the sensor has no centre). Its centre follows options.centre_rule
//     (centre_estimation.h), its width is the first-to-last distance (Algorithm 1, step 9).
//  5. Features are returned in increasing bearing (ties: increasing range).
//
// Measurement covariance of (range, bearing), with R the estimated object radius, D the centre
// range, delta the cluster's mean beam spacing and f = shape_sigma_fraction:
//   var(range)   = sigma_r^2 + (f R)^2            (+ R^2 for kMiddlePoint: its centre is about
//                                                   one radius in front of the object's)
//   var(bearing) = bearing_sigma^2 + delta^2 / 24 + (f R / D)^2
//   cov          = 0
// sigma_r^2 is one beam's range noise (not divided by the point count: neighbouring returns of
// one surface do not have independent errors); delta^2 / 24 is the variance of the middle of
// two edges each uniformly uncertain over one beam spacing; the shape terms cover objects that
// are not circles. Every term is finite and sigma_r, bearing_sigma > 0, so the covariance is
// always positive definite.
//
// Nothing here allocates once the buffers have grown to the largest scan seen.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "perception/breakpoint_criterion.h"
#include "perception/feature.h"
#include "perception/scan_view.h"
#include "perception/segmenter_options.h"

namespace slammtt {

// What happened to one scan's beams and clusters (the stage reports these as counters).
struct SegmentationStats {
  int64_t beams = 0;                   // beams in the scan
  int64_t beams_used = 0;              // beams that took part in the clustering
  int64_t beams_flagged_invalid = 0;   // valid == 0
  int64_t beams_non_finite = 0;        // flagged valid, but NaN or infinite angle or range
  int64_t beams_out_of_range = 0;      // range outside the limits
  int64_t beams_duplicate = 0;         // same direction as a kept beam (the farther is dropped)
  bool beams_were_reversed = false;    // true when the input was mostly clockwise
  bool beams_were_sorted = false;      // true when (after any reversal) it needed sorting
  int64_t clusters = 0;                // clusters found
  int64_t clusters_too_few_points = 0; // fewer than min_points
  int64_t clusters_too_wide = 0;       // wider than max_width_m or spanning pi or more
  int64_t clusters_across_seam = 0;    // clusters holding both the last and the first beam
  int64_t circle_fit_fallbacks = 0;    // kCircleFit only: features that used kRadiusCorrected
  int64_t features = 0;
};

class Segmenter {
 public:
  // Throws std::invalid_argument with CheckSegmenterOptions()'s message for unusable options.
  explicit Segmenter(const SegmenterOptions& options);

  // Segments one scan. The result stays valid until the next call. Any input is accepted: bad
  // beams are dropped and counted in stats(), never a crash or a NaN in the result.
  const std::vector<Feature>& Segment(const ScanView& scan);

  // Segment() in its three steps, for a caller that times them (the stage adapter); call them
  // in this order. PrepareBeams: steps 1-2 (filter, order, duplicates). FindClusters: step 3.
  // MakeFeatures: steps 4-5, returns what Segment() returns.
  void PrepareBeams(const ScanView& scan);
  void FindClusters();
  const std::vector<Feature>& MakeFeatures();

  const SegmentationStats& stats() const { return stats_; }
  const SegmenterOptions& options() const { return options_; }

 private:
  struct Beam {
    double angle_rad;         // wrapped to (-pi, pi]
    double range_m;
    int32_t index;            // position in the input scan
    int32_t unusable_before;  // beams without a usable return between it and the previous
                              // usable beam, in angle order; -1 marks such a beam itself
  };
  struct Cluster {
    size_t ring_start;  // ring index of the first point
    size_t count;
  };
  void CollectBeams(const ScanView& scan);
  void PutInCircularOrder();
  void CountGapsAndDropDuplicates();
  void MakeFeature(const Cluster& cluster);

  SegmenterOptions options_;
  BreakpointCriterion criterion_;
  SegmentationStats stats_;
  std::vector<Beam> beams_;          // the ring of usable beams in circular angle order
  std::vector<uint8_t> splits_;      // splits_[k]: a break between ring k and k + 1 (mod size)
  std::vector<Cluster> clusters_;
  std::vector<double> bearing_;      // one cluster's unwrapped bearings...
  std::vector<double> range_;        // ...ranges...
  std::vector<double> x_;            // ...and Cartesian points
  std::vector<double> y_;
  std::vector<Feature> features_;
};

// One-shot convenience: a Segmenter for one scan (allocates; use a Segmenter in loops).
std::vector<Feature> SegmentScan(const ScanView& scan, const SegmenterOptions& options);

}  // namespace slammtt
