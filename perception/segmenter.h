// Adaptive breakpoint segmentation of one laser scan into point features: the paper's
// Algorithm 1 (section 3) made safe for real scans.
//
// Per scan:
//  0. A scan with more than max_beams_per_scan beams keeps every k-th, k = ceil(beams / cap);
//     the others are counted (beams_over_cap).
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
//  4. Straight structure (options.extract_lines; line_extraction.h), with the split distance
//     line_split_distance_m + line_split_range_fraction * (the cluster's mean range): every
//     cluster of at least
//     min_line_points points is split and merged into straight runs; runs of at least
//     min_line_points points and min_line_length_m are fitted (total least squares) and become
//     line features, and such a cluster gives no point feature, unless it is no wider than
//     max_width_m and one circle (radius <= max_width_m, centre behind the points) fits it
//     about as well as its straight runs (RMS at most 1.1 times theirs with two runs or more,
//     0.7 times with one): a large round object approximated by chords is not a wall.
//     Lines of neighbouring clusters (a wall cut by eq. 15 at grazing incidence, or behind a
//     leg) whose joint fit keeps every point within the split distance are one line.
//  5. Every other cluster: fewer than min_points points is no feature; one point alone is
//     counted as a mixed pixel (its range between those of both angular neighbours) or an
//     isolated beam; two points may be a provisional leg (step 7). A cluster becomes a point
//     feature when the distance between its first and last point is at most max_width_m and
//     it spans less than pi (a cluster that surrounds the sensor has no centre), and it is not
//     a piece of a line of this scan (every point within the split distance of one; if it
//     has more than three points and looks like a leg, every point within 0.025 m of one: a
//     leg's round outline departs farther from a line), and, in a scan with a line
//     feature, not a piece of structure too short for a line: straight (every point within
//     the split distance of its chord) and either at least straight_piece_width_m wide with
//     at least min_line_points points, or with both edges hidden by nearer objects; or at
//     least straight_piece_width_m wide with at least min_line_points points, not leg-like
//     and not explained by a circle as in step 4 (a corner of short walls). Its centre follows
//     options.centre_rule (centre_estimation.h), its width is the first-to-last distance
//     (Algorithm 1, step 9), its leg_likeness comes from its shape (leg_likeness.h).
//  6. Point features are returned in increasing bearing (ties: increasing range), lines in the
//     order of their clusters and runs (CCW from the first cluster).
//  7. People (options.detect_people; person_detection.h): point features with leg_likeness >=
//     leg_threshold, and two-point clusters as provisional legs where a leg of
//     leg_nominal_diameter_m would show fewer than min_points beams, are paired into person
//     features; a provisional leg that joins a person becomes a point feature (inserted in
//     bearing order), the others are dropped. leg_index points into the final features. A
//     candidate that is flat (convexity below 0.1, leg_features.h; a leg shows about 0.7) and
//     has no usable return on either side (Feature::bounded_edges == 0) may be a visible piece
//     of a larger surface: it is a LegCandidate::surface_piece, which makes no person alone and
//     no pair with another. Optionally (both off by default, person_detection.h): a one-leg
//     person stands at least person.single_leg_surface_clearance_m in front of every line
//     feature of the scan, and the pieces of a wall between dropouts (three or more clusters in
//     a row with nothing but beams without a return around and between them, on one straight
//     line) make no person (person.separate_dropout_pieces).
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
#include "perception/leg_classifier.h"
#include "perception/leg_features.h"
#include "perception/line_extraction.h"
#include "perception/person_detection.h"
#include "perception/scan_view.h"
#include "perception/segmenter_options.h"

namespace slammtt {

// What happened to one scan's beams and clusters (the stage reports these as counters).
struct SegmentationStats {
  int64_t beams = 0;                   // beams in the scan
  int64_t beams_over_cap = 0;          // left out: beyond max_beams_per_scan (every k-th kept)
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
  int64_t beams_mixed_pixel = 0;       // one-beam clusters between a nearer and a farther surface
  int64_t beams_isolated = 0;          // other one-beam clusters
  int64_t depth_edges = 0;             // neighbour pairs across a range jump > depth_edge_m
  int64_t clusters_structure = 0;      // clusters that gave line features
  int64_t clusters_round = 0;          // had straight runs, but a circle explains them as well
  int64_t clusters_on_lines = 0;       // compact clusters lying on a line of the scan
  int64_t clusters_structure_pieces = 0;  // too short for lines, but straight or corners
  int64_t beams_on_lines = 0;          // beams in the runs of line features
  int64_t lines = 0;
  int64_t features = 0;
  int64_t leg_candidates = 0;          // point features with leg_likeness >= leg_threshold
  int64_t provisional_legs = 0;        // two-point clusters offered as provisional legs...
  int64_t provisional_legs_used = 0;   // ...and those that joined a person
  // Leg candidates dropped as stubs: no person, no point feature (person_detection.h,
  // single_leg_open_edge_max_points).
  int64_t leg_stubs = 0;
  int64_t people = 0;
  int64_t people_one_leg = 0;
};

// Every cluster whose leg-likeness was computed in one scan (step 5: the compact clusters of
// at least min_points points and the two-point clusters offered as provisional legs), whether
// or not it then became a point feature: what the leg classifier saw. The training program
// (tools/legs) reads these, so it learns from exactly the clusters and features that the
// classifier meets at run time.
enum class LegClusterFate {
  kPointFeature,    // a point feature (or a provisional leg, which FindPeople may drop)
  kStructurePiece,  // a straight piece or a corner of structure too short for a line
  kOnALine,         // its points lie on a line feature of the scan
  kNotALeg,         // a two-point cluster that does not look like a leg
};

struct LegClusterRecord {
  LegFeatureVector features{};
  double centroid_x_m = 0.0;  // mean of the cluster's points, sensor frame
  double centroid_y_m = 0.0;
  double leg_likeness = 0.0;
  LegClusterFate fate = LegClusterFate::kPointFeature;
};

class Segmenter {
 public:
  // Throws std::invalid_argument with CheckSegmenterOptions()'s message for unusable options.
  explicit Segmenter(const SegmenterOptions& options);

  // Segments one scan. The result stays valid until the next call. Any input is accepted: bad
  // beams are dropped and counted in stats(), never a crash or a NaN in the result.
  const std::vector<Feature>& Segment(const ScanView& scan);

  // Segment() in its steps, for a caller that times them (the stage adapter); call them in
  // this order. PrepareBeams: steps 1-2 (filter, order, duplicates). FindClusters: step 3.
  // ExtractLines: step 4. MakeFeatures: steps 5-6. FindPeople: step 7, returns what Segment()
  // returns.
  void PrepareBeams(const ScanView& scan);
  void FindClusters();
  void ExtractLines();
  void MakeFeatures();
  const std::vector<Feature>& FindPeople();

  // The point features, lines and people of the last scan (valid until the next call).
  const std::vector<Feature>& features() const { return features_; }
  const std::vector<LineFeature>& lines() const { return lines_; }
  const std::vector<PersonFeature>& people() const { return people_; }
  const std::vector<LegClusterRecord>& leg_clusters() const { return leg_clusters_; }
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
  // The beams of a line: count beams from ring_start, of which the first skip_first and the
  // last skip_last are in its extent but not in its fit (FitRangesOfRuns).
  struct RingRun {
    size_t ring_start;
    size_t count;
    size_t skip_first;
    size_t skip_last;
    bool merged;  // two runs joined by MergeCollinearLines()
  };

  void CollectBeams(const ScanView& scan);
  void PutInCircularOrder();
  void CountGapsAndDropDuplicates();
  size_t Next(size_t k) const { return k + 1 < beams_.size() ? k + 1 : 0; }
  size_t Previous(size_t k) const { return k > 0 ? k - 1 : beams_.size() - 1; }
  void CountDepthEdges();
  bool ExplainedByCircle(size_t count, double lines_rms_m, size_t runs) const;
  void FillRunPoints(size_t ring_start, size_t count, size_t offset);
  Eigen::Vector2d BeamPoint(size_t k) const;  // ring beam k in the sensor frame
  double SplitDistance(double range_m) const;
  double MeanRange(size_t count) const;  // of sensor_x_, sensor_y_ [0, count)
  size_t LastBeam(const RingRun& run) const;  // ring index of the run's last beam
  // Fills sensor_x_/sensor_y_ from offset with the fitted beams of run; returns their count.
  size_t FillFitPoints(const RingRun& run, size_t offset);
  // The line fitted to sensor_x_/sensor_y_ [0, fit_count), its extent from the first beam of
  // `first` to the last beam of `last` (the same run, or two merged ones).
  LineFeature MakeLine(size_t fit_count, const RingRun& first, const RingRun& last);
  bool TryMergeLines(size_t first, size_t second, LineFeature* merged);
  void MergeCollinearLines();
  void ClassifyLoneBeam(const Cluster& cluster);
  // Every point of sensor_x_/sensor_y_ [0, count) within tolerance_m of one line of lines_.
  bool LiesOnALine(size_t count, double tolerance_m) const;
  void FillSensorFromCluster(size_t count, double reference_bearing_rad);
  bool IsStructurePiece(const ClusterView& cluster, double width_m, bool leg_like);
  void MakeFeature(const Cluster& cluster);
  double ScoreLegLikeness(const ClusterView& cluster, size_t ring_start, size_t last_ring_index,
                          double spacing_rad, double reference_bearing_rad, int* bounded_edges);

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
  std::vector<double> sensor_x_;     // one cluster's points in the sensor frame
  std::vector<double> sensor_y_;
  std::vector<PointRun> runs_;
  std::vector<PointRun> run_stack_;
  std::vector<FitRange> run_fits_;
  std::vector<uint8_t> structure_;   // structure_[c]: cluster c gave line features
  std::vector<Feature> features_;
  std::vector<Feature> provisional_; // two-point leg candidates
  std::vector<LineFeature> lines_;
  std::vector<RingRun> line_runs_;   // the beams of each line, parallel to lines_
  std::vector<LegClusterRecord> leg_clusters_;
  const LegModel* leg_model_ = nullptr;
  std::vector<LegCandidate> candidates_;
  std::vector<uint8_t> candidate_used_;
  std::vector<int32_t> final_index_;
  std::vector<Feature> merged_;
  std::vector<PersonFeature> people_;
  // LegCandidate::dropout_run of every candidate (person_detection.h); called only when
  // person.separate_dropout_pieces reads it (else every candidate keeps -1).
  void FindDropoutRuns();
  std::vector<int32_t> ring_of_input_;
  std::vector<int32_t> piece_at_ring_;
  std::vector<uint8_t> dropped_;  // FindPeople: 1 for a point feature dropped as a stub
  std::vector<int32_t> piece_next_;
  std::vector<uint8_t> piece_has_previous_;
  std::vector<int32_t> piece_run_;
  // The scan's usable beams in increasing angle, for the one-leg centre (person_detection.h).
  const SightLines* SightLinesOfScan();
  std::vector<double> sight_angle_;
  std::vector<double> sight_range_;
  SightLines sight_;
  PersonDetector person_detector_;
};

// One-shot convenience: a Segmenter for one scan (allocates; use a Segmenter in loops).
std::vector<Feature> SegmentScan(const ScanView& scan, const SegmenterOptions& options);

}  // namespace slammtt
