// Where a cluster's point feature is: the three centre rules of SegmenterOptions::centre_rule.
//
// The paper takes the middle point of the cluster (Algorithm 1, step 8). On a round object
// (a person's legs and body, a post, a pillar) the laser sees only the near half of the outline,
// so that point is about one radius in front of the object's centre, and the error changes with
// the viewpoint: a static post seen from two sides seems to move by a diameter. The other two
// rules estimate the centre behind the visible arc. tests/perception/centre_rule_test.cc compares
// them on noisy arcs with known centres; docs/perception.md gives the figures.
#pragma once

#include <Eigen/Core>
#include <cstddef>

namespace slammtt {

// One cluster in counter-clockwise order, parallel arrays of `count` points in a frame with its
// origin at the sensor: bearing_rad is unwrapped (strictly increasing), x_m = range_m *
// cos(bearing_rad), y_m = range_m * sin(bearing_rad). The frame may be rotated (the segmenter
// turns it to the cluster's middle); estimates come back in the same frame. count >= 1,
// ranges > 0.
struct ClusterView {
  const double* bearing_rad = nullptr;
  const double* range_m = nullptr;
  const double* x_m = nullptr;
  const double* y_m = nullptr;
  size_t count = 0;
  // The beam just outside the first (last) point is close in angle and nearer: the cluster's
  // edge there is where another object hides it, not the object's own outline.
  bool first_edge_occluded = false;
  bool last_edge_occluded = false;
};

struct CentreEstimate {
  double range_m = 0.0;
  double bearing_rad = 0.0;  // in the unwrapped frame of ClusterView::bearing_rad
  double radius_m = 0.0;     // object radius behind the centre (0: centre on the outline)
  bool fell_back = false;    // kCircleFit only: the fit was rejected, kRadiusCorrected is used
};

// The paper's rule: the middle point (odd count), or the midpoint of the two middle points (even).
CentreEstimate MiddlePointCentre(const ClusterView& cluster);

// The circle tangent to the two rays that bound the visible extent. The true tangent rays lie
// somewhere between each edge beam and the next beam, which missed, so the visible extent is
// taken as (last - first bearing) + one mean beam spacing, alpha; the centre's bearing is the
// middle of the extent. A circle of radius R whose centre is at distance D subtends
// 2 asin(R / D), so R = D s with s = sin(alpha / 2). Each point p at angle phi from the centre
// ray lies on the near side of that circle when
//   D = r (cos phi + sqrt(s^2 - sin^2 phi)) / (1 - s^2),
// and D is the mean of these per-point values weighted by (s^2 - sin^2 phi) / s^2 (1 at the
// middle of the arc, 0 at the edges, where the square root amplifies every error). A radius
// above max_radius_m is clamped to it, and D refitted with that radius. One point: the point.
CentreEstimate RadiusCorrectedCentre(const ClusterView& cluster, double max_radius_m);

// Least-squares circle fit of the points and of the two tangent rays. Unknowns: centre range D,
// centre bearing theta, radius R. Measurements, each divided by its standard deviation:
//  - every point: its distance to the circle, |p_i - c| - R, with sigma_r_m;
//  - each edge not marked occluded: the tangent ray theta -/+ asin(R / D) against the edge
//    beam's bearing -/+ half a beam spacing, with delta / sqrt(12) (the true tangent lies
//    anywhere between the edge beam and the next beam, which missed).
// Gauss-Newton from RadiusCorrectedCentre(), R kept in (0, min(max_radius_m, 0.99 D)]. With both
// tangents the start is consistent and ONE step is taken (Le Cam's one-step estimator: as
// efficient as iterating to convergence; on tests/perception/centre_rule_test.cc's arcs the
// median errors are equal within 0.4 mm, at half the cost). With a tangent missing the start is
// biased, and up to three steps are taken (fewer when no parameter moves by 0.1 mm). A plain
// circle fit of a short noisy arc is poorly conditioned (the curvature of ten points with 3 cm
// noise says little); the tangents are what pins the radius down, and the points fix the range. With an occluded edge (the neighbouring beam is nearer: another object hides
// part of this one) that tangent is dropped, so a partly hidden object keeps its true size.
// Falls back (fell_back = true, RadiusCorrectedCentre()) when fewer than three measurements
// remain or fewer than kMinCircleFitPoints points are left with no tangent at all, or when the
// normal equations are singular or the result is not finite.
inline constexpr size_t kMinCircleFitPoints = 5;
CentreEstimate CircleFitCentre(const ClusterView& cluster, double max_radius_m, double sigma_r_m);

// The circle of CircleFitCentre(): centre at range distance_m and bearing bearing_rad from the
// sensor, radius radius_m, with what its residuals share (cos and sin of the bearing, the centre
// in x and y, the half angle asin(R / D) it subtends and its derivatives; those are NaN when
// R >= D).
struct FitCircle {
  FitCircle(double distance_m, double bearing_rad, double radius_m);
  double distance_m;
  double bearing_rad;
  double radius_m;
  double cos_bearing;
  double sin_bearing;
  double centre_x_m;
  double centre_y_m;
  double half_angle_rad;       // g = asin(R / D)
  double d_half_angle_d_distance;  // dg / dD = -R / (D sqrt(D^2 - R^2))
  double d_half_angle_d_radius;    // dg / dR = 1 / sqrt(D^2 - R^2)
};

// The fit's residual of a point (x_m, y_m): its distance to the circle, |p - c| - R, and its
// Jacobian with respect to (D, theta, R). False (and nothing written) when the point is at the
// centre, where the distance has no gradient.
bool CirclePointResidual(const FitCircle& circle, double x_m, double y_m, double* residual_m,
                         Eigen::Vector3d* jacobian);

// The bearing of the circle's tangent ray on one side, theta - g (side -1: the first edge, at
// the smaller bearing) or theta + g (side +1: the last edge), and its Jacobian with respect to
// (D, theta, R). The fit's tangent residual is this minus the edge's expected tangent bearing.
double CircleTangentBearing(const FitCircle& circle, int side, Eigen::Vector3d* jacobian);

}  // namespace slammtt
