// Straight structure inside one cluster of a scan: split-and-merge (Nguyen, Gächter, Martinelli,
// Tomatis, Siegwart, "A comparison of line extraction algorithms using 2D laser rangefinder for
// indoor mobile robotics", IROS 2005, section III-A: recursive split at the point farthest from
// the chord, then merge of collinear neighbours) followed by a total-least-squares fit of each
// run with the covariance of its (rho, alpha) (Arras and Siegwart, "Feature extraction and scene
// interpretation for map-based navigation and map building", SPIE 1997; Pfister, Roumeliotis,
// Burdick, "Weighted line fitting algorithms for mobile robot map building and efficient data
// representation", ICRA 2003, eq. 9-12 with equal weights).
//
// Frames: points are Cartesian in one frame whose origin is the sensor (the segmenter passes
// the sensor frame: x forward, y left). Lines are in Hessian normal form,
//   x cos(alpha) + y sin(alpha) = rho,  rho >= 0,  alpha in (-pi, pi],
// alpha the direction of the normal from the sensor towards the line.
//
// Pure: no allocation once the caller's buffers have grown, no libm call per point.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace slammtt {

// A straight piece of structure seen in one scan (a wall, a side of a desk or a cabinet).
struct LineFeature {
  double rho_m = 0.0;      // distance from the sensor to the infinite line, >= 0
  double alpha_rad = 0.0;  // direction of the line's normal from the sensor, (-pi, pi]
  // Covariance of (rho_m, alpha_rad): [m^2, m rad; m rad, rad^2], symmetric positive definite.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  // Observed extent: the first and last point of the run (in CCW scan order) projected onto
  // the line, sensor frame [m].
  Eigen::Vector2d first_point_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_point_m = Eigen::Vector2d::Zero();
  int num_points = 0;           // beams the line is fitted to (a run's beams but a left-out
                                // shared corner: SegmenterOptions::line_fit_without_shared_corners)
  double rms_residual_m = 0.0;  // RMS perpendicular distance of those beams from the line
  // Input indices (positions in the scan as given) of the first and last beam of the run.
  int32_t first_beam_index = -1;
  int32_t last_beam_index = -1;
};

// Total-least-squares fit of a line to points (x_m[i], y_m[i]), i < count, count >= 2.
// Covariance: every point's error perpendicular to the line is taken as independent with
// variance k (range_sigma^2 cos^2(phi) + (r bearing_sigma)^2 sin^2(phi)), phi the angle between
// the beam and the line's normal, k = max(1, (sum e_i^2 / (n - 2)) / mean model variance): the
// fit's own scatter scales the model up when the surface or the sensor is rougher than the
// model says (never down). With s_i the points' coordinates along
// the line from their centroid c, S = sum s_i^2, t the line's direction (d normal / d alpha):
//   var(alpha) = sum s_i^2 sigma_i^2 / S^2,  var(d) = sum sigma_i^2 / n^2,
//   cov(d, alpha) = -sum s_i sigma_i^2 / (n S),  rho = d + (t . c) alpha to first order,
// so var(rho) = var(d) + 2 (t.c) cov(d, alpha) + (t.c)^2 var(alpha) and cov(rho, alpha) =
// cov(d, alpha) + (t.c) var(alpha) (Pfister et al. 2003, eq. 12, equal weights).
// Degenerate input (fewer than 2 points, all points at one place): rho, alpha of the mean
// point's direction, covariance 1e6 I (never singular, never NaN for finite input).
struct LineFit {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  double rms_residual_m = 0.0;
  double centroid_x_m = 0.0;
  double centroid_y_m = 0.0;
};
LineFit FitLine(const double* x_m, const double* y_m, size_t count, double range_sigma_m,
                double bearing_sigma_rad);

// Mean of the points (x_m[i], y_m[i]), i < count; the origin for count 0.
Eigen::Vector2d Centroid(const double* x_m, const double* y_m, size_t count);

// Algebraic circle fit (Kasa, "A circle fitting procedure and its error analysis", IEEE Trans.
// Instrumentation and Measurement 25(1), 1976) about the points' centroid: the centre and
// radius minimising sum ((x - cx)^2 + (y - cy)^2 - R^2)^2, then the geometric RMS residual
// sqrt(mean (|p_i - c| - R)^2). ok is false (and the rest 0) for fewer than three points,
// collinear points or a non-finite solution.
struct CircleFit {
  bool ok = false;
  double centre_x_m = 0.0;
  double centre_y_m = 0.0;
  double radius_m = 0.0;
  double rms_residual_m = 0.0;
};
CircleFit FitCircleKasa(const double* x_m, const double* y_m, size_t count);

// Signed distance of (x, y) from the line of a fit (positive on the far side from the sensor).
inline double DistanceFromLine(double rho_m, double cos_alpha, double sin_alpha, double x_m,
                               double y_m) {
  return x_m * cos_alpha + y_m * sin_alpha - rho_m;
}

// Largest distance of the points [0, count) from the chord between the first and the last (0
// for fewer than three points).
double MaxDistanceFromChord(const double* x_m, const double* y_m, size_t count);

// A run of consecutive points [begin, end) of a cluster.
struct PointRun {
  size_t begin = 0;
  size_t end = 0;
  size_t size() const { return end - begin; }
};

// Split-and-merge of the ordered points [0, count): a run is split at its point farthest from
// the chord between its ends while that distance exceeds split_distance_m (runs of 2 points
// are never split); then neighbouring runs are merged while the points of both lie within
// split_distance_m of the chord of the union (Nguyen et al. 2005, "split-and-merge", with the
// chord test, their "iterative end-point fit" variant, for both steps). Fills `runs` in point
// order; `stack` is scratch space. count == 0 gives no run.
void SplitAndMerge(const double* x_m, const double* y_m, size_t count, double split_distance_m,
                   std::vector<PointRun>* runs, std::vector<PointRun>* stack);

// SplitAndMerge leaves the point it splits at in both runs. A measured point lies on one
// surface, and the scan cannot tell which: at an occlusion edge the first beam past the edge
// hits the surface behind, seen obliquely a few centimetres off the nearer surface's extension
// and always on the same side of it; at a convex corner it is the beam nearest the corner, on
// one of the two sides. In both fits it turns the other surface's line (office scenario: such
// points are one cause of a 0.4 m cabinet side's landmark being 2.5-3.3 degrees off on every
// seed; docs/perception.md, "Line features"). FitRangesOfRuns gives, for each run of `runs` (in
// point order, as SplitAndMerge gives them), the points its line is fitted to: the whole run,
// or with leave_out_shared_corners a point shared by two neighbouring runs left out of the fit
// of each that keeps at least two points without it. The runs themselves (the extent the scan
// saw) are not changed.
struct FitRange {
  size_t fit_begin = 0;
  size_t fit_end = 0;
};
void FitRangesOfRuns(const std::vector<PointRun>& runs, bool leave_out_shared_corners,
                     std::vector<FitRange>* fits);

}  // namespace slammtt
