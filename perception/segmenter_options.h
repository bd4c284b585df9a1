// Parameters of the adaptive breakpoint segmentation (paper section 3, Algorithm 1) and of the
// point feature made from each cluster. Defaults are the paper's where it gives one (lambda,
// sigma_r); the others are ours, chosen and justified in docs/perception.md.
//
// VisitSegmenterOptions lists every option once (key, range, unit, doc; common/options_schema.h):
// the reader of the stack configuration's `segmenter:` section (ReadSegmenterOptions() in
// perception/segmenter_stage.h), CheckSegmenterOptions and the table of docs/perception.md
// come from it.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "common/options_schema.h"
#include "perception/leg_classifier.h"
#include "perception/leg_likeness.h"
#include "perception/person_detection.h"

namespace slammtt {

// Where the feature's centre is put (the point handed to the estimator).
enum class CentreRule {
  // The paper's rule (Algorithm 1, step 8): the middle point of the cluster. On a round object
  // (person, post) every visible point lies on the near half of the outline, so this centre is
  // about one radius closer to the sensor than the object's centre.
  kMiddlePoint,
  // Bearing: middle of the cluster's angular extent. Range: the circle tangent to the two rays
  // that bound the visible extent, fitted to the central points along the beams; i.e. the near
  // range pushed back by a radius estimated from the extent (see centre_estimation.h).
  kRadiusCorrected,
  // Least-squares circle fit of the cluster's points and of the two tangent rays that bound it
  // (an edge hidden by a nearer object is left out), one Gauss-Newton step from
  // kRadiusCorrected; kRadiusCorrected is used when the fit cannot be made.
  kCircleFit,
};

// How a point feature's leg_likeness is computed.
enum class LegClassifier {
  // P(leg) from the learned model (leg_classifier.h) on the cluster's features
  // (leg_features.h): SegmenterOptions::leg_model, by default TrainedLegModel().
  kTrained,
  // The hand-written shape score of leg_likeness.h (width, convexity, edges).
  kShape,
};

// "trained", "shape".
const char* LegClassifierName(LegClassifier classifier);
// Parses a name of LegClassifierName(); false for anything else.
bool ParseLegClassifier(const std::string& name, LegClassifier* classifier);

// "middle_point", "radius_corrected", "circle_fit".
const char* CentreRuleName(CentreRule rule);
// Parses a name of CentreRuleName(); false for anything else.
bool ParseCentreRule(const std::string& name, CentreRule* rule);

struct SegmenterOptions {
  // Breakpoint criterion (paper eq. 15, Borges and Aldon 2004): consecutive points i, i+1 are
  // split when |p(i+1) - p(i)| > r(i) * sin(dtheta) / sin(lambda - dtheta) + 3 * sigma_r.
  // lambda is the smallest incidence angle of a surface that still counts as one object.
  double lambda_rad = 20.0 * M_PI / 180.0;  // paper: 20 degrees
  double sigma_r_m = 0.03;                  // paper: 0.03 m; also the range noise of one beam

  // More than this many beams without a usable return between two valid neighbours always
  // split (counted in angle order, so it means the same at any angular resolution and in either
  // RPLIDAR mode, 1.8 or 0.9 degrees). A real RPLIDAR drops single beams on dark or shiny
  // surfaces: the default bridges one, so such a dropout does not cut a person in two.
  // The price: two objects with exactly one no-return beam between them stay one cluster
  // (crowd-zara02 recall 0.93 with 1, 0.96 with 0; docs/perception.md).
  int max_dropped_beams = 1;
  // Two valid beams further apart than this always split, whatever eq. 15 says: the bound for
  // drivers that leave no-return beams out of the scan, where gaps cannot be counted. Eq. 15
  // alone joins points across any gap below lambda, and its threshold grows fast with the gap
  // (at 27 m a 3-degree gap allows 4.9 m).
  double max_beam_gap_rad = 5.0 * M_PI / 180.0;

  // Beams whose angles differ by less than this are one direction measured twice; the nearer
  // return is kept (the far one of a pair is a mixed or late return). Far below any real
  // spacing (RPLIDAR quantises angles to 1/64 degree), above float rounding near 2 pi.
  double duplicate_angle_tolerance_rad = 0.001 * M_PI / 180.0;

  // The most beams of one scan that are segmented. A scan with more keeps every k-th beam in
  // input order, k = ceil(num_beams / max_beams_per_scan) (the whole view at a coarser
  // resolution, not a cut-off sector), and the others are counted (beams_over_cap) and
  // reported. Bounds the cost of a hostile scan: a million beams made one scan take 11.9 s, the
  // leg pairing alone being quadratic in the clusters. 8192 is above every laser the stack
  // takes: RPLIDAR A2 at most 8000 samples/s at 5 Hz (1600), Hokuyo UTM-30LX 1081, SICK LMS
  // 0.1667 degrees 2161 (docs/perception.md, "Hostile sizes").
  int max_beams_per_scan = 8192;

  // Range limits, applied together with the scan's own range_min_m / range_max_m (the tighter
  // limit wins). Beams outside are dropped and counted.
  double min_range_m = 0.0;
  double max_range_m = std::numeric_limits<double>::infinity();

  // A cluster becomes a feature only with at least this many points...
  int min_points = 3;
  // ...and when the distance between its first and last point is at most this: a wall or a
  // long piece of furniture is not a point feature (its "centre" slides with the viewpoint and
  // the estimator would take it for a moving object). People are about 0.5 m wide.
  double max_width_m = 1.5;

  CentreRule centre_rule = CentreRule::kCircleFit;
  // Upper bound of an object radius for kRadiusCorrected and kCircleFit: larger estimates are
  // clamped to it.
  double max_object_radius_m = 1.0;

  // Measurement covariance of the feature (see Segmenter in segmenter.h for the model):
  // angular noise of one beam's direction (encoder jitter, timing within the revolution).
  double bearing_sigma_rad = 0.5 * M_PI / 180.0;
  // Fraction of the estimated object radius taken as the standard deviation of the centre's
  // position from the object's shape (objects are not exact circles).
  double shape_sigma_fraction = 0.3;

  // Straight structure (line_extraction.h; segmenter.h, steps 4-5): inside every cluster of
  // at least min_line_points points, split-and-merge with the split distance
  // (line_split_distance_m + line_split_range_fraction * mean range); each run of at least
  // min_line_points points and min_line_length_m from end to end is a line feature, and the
  // cluster gives no point feature (unless one circle of radius at most max_width_m explains
  // it as well as its runs: a large round object is not a wall). A compact cluster all of
  // whose points lie within the split distance of a line of the same scan is a piece of that
  // structure (a wall seen between two legs, a wall at grazing incidence broken up by eq. 15)
  // and gives no point feature either, unless it looks like a leg (leg_likeness >=
  // leg_threshold) and has more than three points. false: no line features, walls are
  // clusters_too_wide as in the paper's algorithm.
  // In a scan with a line feature, a compact cluster is a piece of structure too short for a
  // line, not a point feature, when it is straight (every point within the split distance of
  // its chord) and either at least straight_piece_width_m wide (wider than a leg) with at
  // least min_line_points points, or with both edges hidden by nearer objects (background
  // seen between two of them); or when it is at least straight_piece_width_m wide with
  // min_line_points points, not leg-like, and no circle explains it (a corner).
  bool extract_lines = true;
  double straight_piece_width_m = 0.2;
  double line_split_distance_m = 0.05;
  // Range noise grows with range (about 1 % for Hokuyo URG-class scanners and the RPLIDAR A2
  // beyond a few metres): the split distance is line_split_distance_m plus this fraction of
  // the cluster's mean range (0.09 m at 4 m), for fragments and merges too.
  double line_split_range_fraction = 0.005;
  int min_line_points = 5;
  double min_line_length_m = 0.4;
  // true: a point that two neighbouring runs share (where split-and-merge split) is left out
  // of both lines' fits, and still bounds their extents (line_extraction.h,
  // FitRangesOfRuns: at an occlusion edge it is the first point on the surface
  // behind). Which runs are lines does not change.
  bool line_fit_without_shared_corners = false;

  // Leg-likeness of every point feature: the learned model's P(leg) (leg_classifier.h), or the
  // hand-written shape score (leg_likeness.h, with `leg` and this struct's sigma_r_m).
  LegClassifier leg_classifier = LegClassifier::kTrained;
  // The model of kTrained; nullptr: TrainedLegModel(). Not owned; must outlive the Segmenter.
  const LegModel* leg_model = nullptr;
  LegLikenessOptions leg;
  // People (person_detection.h) from the point features with leg_likeness >= leg_threshold.
  // A cluster of only two points joins a person as a provisional leg (and then becomes a
  // point feature) where a leg of leg_nominal_diameter_m would show fewer than min_points
  // beams (range r, beam spacing delta: leg_nominal_diameter_m / (r delta) < min_points; at
  // 0.9 degrees beyond about 2.5 m, never at 0.35 degrees within 6 m).
  bool detect_people = true;
  // The trained model's own threshold (chosen by the training program's cross-validation,
  // leg_classifier.h); with kShape the hand-written score was measured at 0.65.
  double leg_threshold = TrainedLegModel().suggested_threshold;
  double leg_nominal_diameter_m = 0.12;
  PersonDetectionOptions person;

  // A cluster of one beam is never a feature. It is a mixed pixel when its range lies between
  // those of its two angular neighbours (a beam that straddled a depth edge and returned a
  // range between the two surfaces), an isolated beam otherwise; both are counted. A depth
  // edge is a pair of neighbouring beams (or a neighbour pair with one lone beam between)
  // whose ranges differ by more than depth_edge_m: the denominator of the mixed-pixel rate.
  double depth_edge_m = 0.3;
};

// The options schema of the segmenter: every option once, with its range (in the unit of the
// configuration), unit and doc, in the order of SegmenterOptions. Keys: the field's name, the
// nested structs' names in front (leg_min_diameter_m, person_max_leg_separation_m), angles in
// degrees (lambda_deg). max_range_m's +infinity (no limit) is written 0. leg_model is not an
// option (a pointer; CheckSegmenterOptions checks it).
void VisitSegmenterOptions(OptionVisitor* visitor, SegmenterOptions* options);

// Empty when the options are usable; otherwise one line naming the first bad option by its key
// ("lambda_deg = 100: must be in (0, 90)"): each value within its range (the schema), then the
// conditions between options (max_range_m > min_range_m, leg_max_diameter_m >=
// leg_min_diameter_m, person_max_leg_separation_m > person_min_leg_separation_m) and a given
// leg_model's own check.
std::string CheckSegmenterOptions(const SegmenterOptions& options);

// The Markdown table of every key of the `segmenter:` section: key, default, valid values,
// one line (docs/perception.md, "Options"; printed by slammtt-segmenter --options-table).
std::string SegmenterOptionsTable();

}  // namespace slammtt
