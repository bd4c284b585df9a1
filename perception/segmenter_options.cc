#include "perception/segmenter_options.h"

#include <sstream>

namespace slammtt {
namespace {

std::string Bad(const char* field, const char* requirement, double value) {
  std::ostringstream out;
  out << field << " must be " << requirement << ", got " << value;
  return out.str();
}

}  // namespace

const char* CentreRuleName(CentreRule rule) {
  switch (rule) {
    case CentreRule::kMiddlePoint:
      return "middle_point";
    case CentreRule::kRadiusCorrected:
      return "radius_corrected";
    case CentreRule::kCircleFit:
      return "circle_fit";
  }
  return "unknown";
}

bool ParseCentreRule(const std::string& name, CentreRule* rule) {
  for (CentreRule candidate :
       {CentreRule::kMiddlePoint, CentreRule::kRadiusCorrected, CentreRule::kCircleFit}) {
    if (name == CentreRuleName(candidate)) {
      *rule = candidate;
      return true;
    }
  }
  return false;
}

std::string CheckSegmenterOptions(const SegmenterOptions& o) {
  // Written as !(x > 0) so that NaN fails every check.
  if (!(o.lambda_rad > 0.0 && o.lambda_rad < 0.5 * M_PI)) {
    return Bad("lambda_rad", "in (0, pi/2)", o.lambda_rad);
  }
  if (!(o.sigma_r_m > 0.0) || !std::isfinite(o.sigma_r_m)) {
    return Bad("sigma_r_m", "positive and finite", o.sigma_r_m);
  }
  if (!(o.max_beam_gap_rad > 0.0) || !std::isfinite(o.max_beam_gap_rad)) {
    return Bad("max_beam_gap_rad", "positive and finite", o.max_beam_gap_rad);
  }
  if (o.max_dropped_beams < 0) return Bad("max_dropped_beams", "at least 0", o.max_dropped_beams);
  if (!(o.duplicate_angle_tolerance_rad >= 0.0 && o.duplicate_angle_tolerance_rad < 0.01)) {
    return Bad("duplicate_angle_tolerance_rad", "in [0, 0.01)", o.duplicate_angle_tolerance_rad);
  }
  if (!(o.min_range_m >= 0.0) || !std::isfinite(o.min_range_m)) {
    return Bad("min_range_m", "non-negative and finite", o.min_range_m);
  }
  if (!(o.max_range_m > o.min_range_m)) {
    return Bad("max_range_m", "greater than min_range_m", o.max_range_m);
  }
  if (o.min_points < 1) return Bad("min_points", "at least 1", o.min_points);
  if (!(o.max_width_m > 0.0) || !std::isfinite(o.max_width_m)) {
    return Bad("max_width_m", "positive and finite", o.max_width_m);
  }
  if (!(o.max_object_radius_m > 0.0) || !std::isfinite(o.max_object_radius_m)) {
    return Bad("max_object_radius_m", "positive and finite", o.max_object_radius_m);
  }
  if (!(o.bearing_sigma_rad > 0.0) || !std::isfinite(o.bearing_sigma_rad)) {
    return Bad("bearing_sigma_rad", "positive and finite", o.bearing_sigma_rad);
  }
  if (!(o.shape_sigma_fraction >= 0.0) || !std::isfinite(o.shape_sigma_fraction)) {
    return Bad("shape_sigma_fraction", "non-negative and finite", o.shape_sigma_fraction);
  }
  if (o.centre_rule != CentreRule::kMiddlePoint && o.centre_rule != CentreRule::kRadiusCorrected &&
      o.centre_rule != CentreRule::kCircleFit) {
    return "centre_rule is not one of middle_point, radius_corrected, circle_fit";
  }
  return "";
}

}  // namespace slammtt
