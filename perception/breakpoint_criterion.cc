#include "perception/breakpoint_criterion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slammtt {

double BreakpointThresholdM(double range_m, double dtheta_rad, double lambda_rad,
                            double sigma_r_m) {
  if (dtheta_rad >= lambda_rad) return std::numeric_limits<double>::infinity();
  return range_m * std::sin(dtheta_rad) / std::sin(lambda_rad - dtheta_rad) + 3.0 * sigma_r_m;
}

BreakpointCriterion::BreakpointCriterion(double lambda_rad, double sigma_r_m, double max_gap_rad)
    : max_dtheta_rad_(std::min(lambda_rad, max_gap_rad)),
      short_series_(max_dtheta_rad_ <= 0.4),
      sin_lambda_(std::sin(lambda_rad)),
      cos_lambda_(std::cos(lambda_rad)),
      three_sigma_m_(3.0 * sigma_r_m) {}

}  // namespace slammtt
