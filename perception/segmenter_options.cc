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

const char* LegClassifierName(LegClassifier classifier) {
  switch (classifier) {
    case LegClassifier::kTrained:
      return "trained";
    case LegClassifier::kShape:
      return "shape";
  }
  return "unknown";
}

bool ParseLegClassifier(const std::string& name, LegClassifier* classifier) {
  for (LegClassifier candidate : {LegClassifier::kTrained, LegClassifier::kShape}) {
    if (name == LegClassifierName(candidate)) {
      *classifier = candidate;
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
  if (o.max_beams_per_scan < 16) {
    return Bad("max_beams_per_scan", "at least 16", o.max_beams_per_scan);
  }
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
  if (!(o.line_split_distance_m > 0.0) || !std::isfinite(o.line_split_distance_m)) {
    return Bad("line_split_distance_m", "positive and finite", o.line_split_distance_m);
  }
  if (!(o.line_split_range_fraction >= 0.0 && o.line_split_range_fraction < 1.0)) {
    return Bad("line_split_range_fraction", "in [0, 1)", o.line_split_range_fraction);
  }
  if (!(o.straight_piece_width_m > 0.0) || !std::isfinite(o.straight_piece_width_m)) {
    return Bad("straight_piece_width_m", "positive and finite", o.straight_piece_width_m);
  }
  if (o.min_line_points < 3) return Bad("min_line_points", "at least 3", o.min_line_points);
  if (!(o.min_line_length_m > 0.0) || !std::isfinite(o.min_line_length_m)) {
    return Bad("min_line_length_m", "positive and finite", o.min_line_length_m);
  }
  if (!(o.leg.leg_min_diameter_m > 0.0) || !std::isfinite(o.leg.leg_min_diameter_m)) {
    return Bad("leg_min_diameter_m", "positive and finite", o.leg.leg_min_diameter_m);
  }
  if (!(o.leg.leg_max_diameter_m >= o.leg.leg_min_diameter_m) ||
      !std::isfinite(o.leg.leg_max_diameter_m)) {
    return Bad("leg_max_diameter_m", "finite and at least leg_min_diameter_m",
               o.leg.leg_max_diameter_m);
  }
  if (!(o.leg.leg_diameter_margin_m > 0.0) || !std::isfinite(o.leg.leg_diameter_margin_m)) {
    return Bad("leg_diameter_margin_m", "positive and finite", o.leg.leg_diameter_margin_m);
  }
  if (!(o.leg.convexity_floor >= 0.0 && o.leg.convexity_floor <= 1.0)) {
    return Bad("convexity_floor", "in [0, 1]", o.leg.convexity_floor);
  }
  if (o.leg_model != nullptr && *CheckLegModel(*o.leg_model) != '\0') {
    return CheckLegModel(*o.leg_model);
  }
  if (!(o.leg_threshold >= 0.0 && o.leg_threshold <= 1.0)) {
    return Bad("leg_threshold", "in [0, 1]", o.leg_threshold);
  }
  if (!(o.leg_nominal_diameter_m > 0.0) || !std::isfinite(o.leg_nominal_diameter_m)) {
    return Bad("leg_nominal_diameter_m", "positive and finite", o.leg_nominal_diameter_m);
  }
  const PersonDetectionOptions& p = o.person;
  if (!(p.min_leg_separation_m >= 0.0) || !std::isfinite(p.min_leg_separation_m)) {
    return Bad("min_leg_separation_m", "non-negative and finite", p.min_leg_separation_m);
  }
  if (!(p.max_leg_separation_m > p.min_leg_separation_m) ||
      !std::isfinite(p.max_leg_separation_m)) {
    return Bad("max_leg_separation_m", "finite and greater than min_leg_separation_m",
               p.max_leg_separation_m);
  }
  if (!(p.single_leg_threshold >= 0.0 && p.single_leg_threshold <= 1.0)) {
    return Bad("single_leg_threshold", "in [0, 1]", p.single_leg_threshold);
  }
  if (!(p.pair_centre_sigma_m > 0.0) || !std::isfinite(p.pair_centre_sigma_m)) {
    return Bad("pair_centre_sigma_m", "positive and finite", p.pair_centre_sigma_m);
  }
  if (!(p.single_leg_offset_sigma_m > 0.0) || !std::isfinite(p.single_leg_offset_sigma_m)) {
    return Bad("single_leg_offset_sigma_m", "positive and finite", p.single_leg_offset_sigma_m);
  }
  if (!(o.depth_edge_m > 0.0) || !std::isfinite(o.depth_edge_m)) {
    return Bad("depth_edge_m", "positive and finite", o.depth_edge_m);
  }
  if (o.centre_rule != CentreRule::kMiddlePoint && o.centre_rule != CentreRule::kRadiusCorrected &&
      o.centre_rule != CentreRule::kCircleFit) {
    return "centre_rule is not one of middle_point, radius_corrected, circle_fit";
  }
  return "";
}

}  // namespace slammtt
