// The adaptive breakpoint criterion of Borges and Aldon ("Line extraction in 2D range images
// for mobile robotics", J. Intell. Robot. Syst. 40 (2004) 267-297), as the paper uses it (eq. 15,
// Algorithm 1 step 3): two consecutive points (r_i, theta_i), (r_j, theta_i + dtheta) of a scan
// belong to different clusters when their Euclidean distance exceeds
//
//   D_max = r_i * sin(dtheta) / sin(lambda - dtheta) + 3 * sigma_r.
//
// Geometry: D_max is how far the next beam's point may be on a surface through p_i that the
// beam i meets at an incidence angle of at least lambda, plus three range standard deviations.
// The paper writes dtheta for the sensor's angular resolution; we use the actual angle between
// the two beams, which is the same on an evenly spaced scan and the right value on an uneven one
// (RPLIDAR) or across a dropped beam. For dtheta >= lambda no surface qualifies: always a break.
#pragma once

#include "perception/trig_series.h"

namespace slammtt {

// Reference form of eq. 15: D_max in metres, +infinity when dtheta_rad >= lambda_rad.
// Preconditions: range_m >= 0, dtheta_rad >= 0, 0 < lambda_rad < pi/2, sigma_r_m >= 0.
double BreakpointThresholdM(double range_m, double dtheta_rad, double lambda_rad,
                            double sigma_r_m);

// The same test, cheap enough for the per-beam loop: no division, no square root and no libm
// call (Taylor series: five terms when every tested angle is below 0.4 rad, as with the default
// 5-degree gap bound, else trig_series.h). For dtheta below max_gap_rad, Splits(r_i, r_j,
// dtheta) is |p_j - p_i| > BreakpointThresholdM(r_i, dtheta, lambda, sigma_r), except within
// ~1e-12 m of the threshold.
class BreakpointCriterion {
 public:
  // max_gap_rad: beams further apart than this always split (SegmenterOptions::max_beam_gap_rad).
  BreakpointCriterion(double lambda_rad, double sigma_r_m, double max_gap_rad);

  // True when point j (range_j_m, at dtheta_rad >= 0 CCW from point i) starts a new cluster
  // after point i (range_i_m). Ranges must be finite and >= 0.
  bool Splits(double range_i_m, double range_j_m, double dtheta_rad) const {
    if (dtheta_rad >= max_dtheta_rad_) return true;
    double sin_d = 0.0;
    double versine_d = 0.0;  // 1 - cos(dtheta), without the cancellation of computing it so
    if (short_series_) {
      // dtheta < 0.4: five terms each, errors below 3e-12 and 4e-14.
      const double x2 = dtheta_rad * dtheta_rad;
      sin_d = dtheta_rad * (1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 +
              x2 * (1.0 / 362880)))));
      versine_d = x2 * (0.5 + x2 * (-1.0 / 24 + x2 * (1.0 / 720 + x2 * (-1.0 / 40320 +
                  x2 * (1.0 / 3628800)))));
    } else {
      const double h = 0.5 * dtheta_rad;  // 0 <= h < pi/4
      const double sin_h = SinSeries(h);
      sin_d = 2.0 * sin_h * CosSeries(h);
      versine_d = 2.0 * sin_h * sin_h;
    }
    const double cos_d = 1.0 - versine_d;
    const double sin_lambda_minus_d = sin_lambda_ * cos_d - cos_lambda_ * sin_d;  // > 0
    // |p_j - p_i|^2 by the law of cosines.
    const double dr = range_j_m - range_i_m;
    const double distance2 = dr * dr + 2.0 * range_i_m * range_j_m * versine_d;
    // distance > r_i sin_d / s + 3 sigma  <=>  distance * s > r_i sin_d + 3 sigma s  (s > 0).
    const double rhs = range_i_m * sin_d + three_sigma_m_ * sin_lambda_minus_d;
    return distance2 * sin_lambda_minus_d * sin_lambda_minus_d > rhs * rhs;
  }

 private:
  double max_dtheta_rad_;  // min(lambda, max_gap); at or beyond it, always a break
  bool short_series_;      // max_dtheta_rad_ <= 0.4: the cheaper series suffice
  double sin_lambda_;
  double cos_lambda_;
  double three_sigma_m_;
};

}  // namespace slammtt
