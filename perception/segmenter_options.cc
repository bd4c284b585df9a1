#include "perception/segmenter_options.h"

#include <limits>

namespace slammtt {

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

void VisitSegmenterOptions(OptionVisitor* v, SegmenterOptions* o) {
  using R = OptionRange;
  const OptionUnit deg = OptionUnit::kDegrees;
  v->Double("lambda_rad", &o->lambda_rad, R::Open(0, 90),
            "lambda of eq. 15 (paper: 20 degrees)", deg);
  v->Double("sigma_r_m", &o->sigma_r_m, R::Above(0),
            "sigma of eq. 15 (3 sigma term) and the range noise of the covariance (paper: 0.03)");
  v->Int("max_dropped_beams", &o->max_dropped_beams, R::Between(0, 100000),
         "more no-return beams in a row between two valid beams always split");
  v->Double("max_beam_gap_rad", &o->max_beam_gap_rad, R::Above(0),
            "valid beams further apart always split (the bound when gaps cannot be counted)",
            deg);
  v->Double("duplicate_angle_tolerance_rad", &o->duplicate_angle_tolerance_rad,
            R{0, 0.5, true, false},
            "closer beams are one direction (RPLIDAR quantises to 1/64 degree)", deg);
  v->Int("max_beams_per_scan", &o->max_beams_per_scan, R::Between(16, 10000000),
         "a scan with more keeps every k-th beam, k = ceil(beams / cap); the rest counted "
         "(`beams_over_cap`) and reported (\"Hostile sizes\")");
  v->Double("min_range_m", &o->min_range_m, R::AtLeast(0),
            "with the scan's `range_min_m`, the tighter wins");
  // The field's +infinity (no limit) is written 0, as a configuration cannot write infinity.
  double max_range_m = o->max_range_m == std::numeric_limits<double>::infinity()
                           ? 0.0
                           : o->max_range_m;
  v->Double("max_range_m", &max_range_m, R::AtLeast(0),
            "with the scan's `range_max_m`, the tighter wins (0: no limit)");
  o->max_range_m = max_range_m == 0.0 ? std::numeric_limits<double>::infinity() : max_range_m;
  v->Int("min_points", &o->min_points, R::Between(1, 100000),
         "points for a feature (the targets count objects seen by >= 3 beams)");
  v->Double("max_width_m", &o->max_width_m, R::Above(0),
            "wider clusters (walls) are not point features; people are about 0.5 m wide");
  int centre_rule = static_cast<int>(o->centre_rule);
  v->Choice("centre_rule", &centre_rule, {"middle_point", "radius_corrected", "circle_fit"},
            "the feature's centre (\"Centre rules\")");
  o->centre_rule = static_cast<CentreRule>(centre_rule);
  v->Double("max_object_radius_m", &o->max_object_radius_m, R::Above(0),
            "radius bound of the corrected rules");
  v->Double("bearing_sigma_rad", &o->bearing_sigma_rad, R::Above(0),
            "angular noise of one beam, for the covariance", deg);
  v->Double("shape_sigma_fraction", &o->shape_sigma_fraction, R::AtLeast(0),
            "shape term of the covariance, fraction of the radius");
  v->Bool("extract_lines", &o->extract_lines,
          "line features and the structure tests; false: the paper's algorithm");
  v->Double("straight_piece_width_m", &o->straight_piece_width_m, R::Above(0),
            "straight or corner pieces at least this wide are structure, not points");
  v->Double("line_split_distance_m", &o->line_split_distance_m, R::Above(0),
            "split-and-merge distance at range 0");
  v->Double("line_split_range_fraction", &o->line_split_range_fraction, R{0, 1, true, false},
            "...plus this fraction of the cluster's mean range");
  v->Int("min_line_points", &o->min_line_points, R::Between(3, 100000),
         "points of a line feature");
  v->Double("min_line_length_m", &o->min_line_length_m, R::Above(0),
            "end-to-end length of a line feature");
  v->Bool("line_fit_without_shared_corners", &o->line_fit_without_shared_corners,
          "the point two runs share is left out of both lines' fits (kept in their extents)");
  int leg_classifier = static_cast<int>(o->leg_classifier);
  v->Choice("leg_classifier", &leg_classifier, {"trained", "shape"},
            "`trained`: P(leg) of the learned model; `shape`: the hand-written score");
  o->leg_classifier = static_cast<LegClassifier>(leg_classifier);
  v->BeginGroup("leg");
  v->Double("min_diameter_m", &o->leg.min_diameter_m, R::Above(0),
            "smallest diameter where the width factor is 1 (`shape` only)");
  v->Double("max_diameter_m", &o->leg.max_diameter_m, R::Above(0),
            "largest diameter where the width factor is 1 (`shape` only)");
  v->Double("diameter_margin_m", &o->leg.diameter_margin_m, R::Above(0),
            "the width factor falls to 0 over this below, three times this above");
  v->Double("convexity_floor", &o->leg.convexity_floor, R::Between(0, 1),
            "convexity factor of a flat or concave cluster (`shape` only)");
  v->EndGroup();
  v->Bool("detect_people", &o->detect_people, "person features");
  v->Double("leg_threshold", &o->leg_threshold, R::Between(0, 1),
            "leg-likeness of a leg candidate (the trained model's; the shape score: 0.65)");
  v->Double("leg_nominal_diameter_m", &o->leg_nominal_diameter_m, R::Above(0),
            "decides where two-beam clusters are provisional legs");
  v->BeginGroup("person");
  v->Double("min_leg_separation_m", &o->person.min_leg_separation_m, R::AtLeast(0),
            "least distance between the two legs of a person");
  v->Double("max_leg_separation_m", &o->person.max_leg_separation_m, R::Above(0),
            "largest distance between the two legs of a person");
  v->Double("single_leg_threshold", &o->person.single_leg_threshold, R::Between(0, 1),
            "leg-likeness of a one-leg person");
  v->Double("pair_centre_sigma_m", &o->person.pair_centre_sigma_m, R::Above(0),
            "body centre vs midpoint of the legs, in the covariance");
  v->Double("single_leg_offset_sigma_m", &o->person.single_leg_offset_sigma_m, R::Above(0),
            "centre vs the one visible leg, in the covariance");
  v->Double("single_leg_open_edge_step", &o->person.single_leg_open_edge_step, R::Between(0, 1),
            "one-leg person: more leg-likeness per edge beside a beam without a usable return");
  v->Double("single_leg_surface_clearance_m", &o->person.single_leg_surface_clearance_m,
            R::AtLeast(0), "one-leg person: least distance of the leg in front of a line feature");
  v->Bool("separate_dropout_pieces", &o->person.separate_dropout_pieces,
          "no pair of two clusters with only beams without a return around and between them");
  v->Int("single_leg_open_edge_max_points", &o->person.single_leg_open_edge_max_points,
         R::AtLeast(0),
         "one-leg person: a leg with an edge beside a beam without a usable return and at most "
         "this many points is a stub, no person and no point feature (0: no such rule)");
  v->Bool("hidden_leg_centre", &o->person.hidden_leg_centre,
          "one-leg person: centre between the leg and where the scan cannot see (false: on the leg)");
  v->EndGroup();
  v->Double("depth_edge_m", &o->depth_edge_m, R::Above(0),
            "range jump of a depth edge (mixed pixels, `depth_edges`)");
}

std::string CheckSegmenterOptions(const SegmenterOptions& options) {
  SegmenterOptions o = options;
  OptionRangeCheck check;
  VisitSegmenterOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  // Conditions between options, on the fields as given (the schema wrote 0 for infinity).
  o = options;
  if (!(o.max_range_m > o.min_range_m)) return "max_range_m must be > min_range_m";
  if (!(o.leg.max_diameter_m >= o.leg.min_diameter_m)) {
    return "leg_max_diameter_m must be >= leg_min_diameter_m";
  }
  if (!(o.person.max_leg_separation_m > o.person.min_leg_separation_m)) {
    return "person_max_leg_separation_m must be > person_min_leg_separation_m";
  }
  if (o.leg_model != nullptr && *CheckLegModel(*o.leg_model) != '\0') {
    return CheckLegModel(*o.leg_model);
  }
  return "";
}

std::string SegmenterOptionsTable() {
  SegmenterOptions defaults;
  OptionsMarkdownTable table;
  VisitSegmenterOptions(&table, &defaults);
  return table.Table();
}

}  // namespace slammtt
