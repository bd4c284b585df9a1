#include "perception/segmenter_stage.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include "runtime/lcm_io.h"
#include "runtime/log.h"
#include "runtime/message_checks.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"

namespace slammtt {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// The scan's utime is the big-endian int64 right after the 8-byte type fingerprint
// (lcmtypes/laser_scan_t.lcm; LCM type specification). The stage reads it before decoding, so
// that the "decode" sub-stage can be timed under the scan's own utime.
constexpr int kUtimeOffset = static_cast<int>(encoded_bytes::kFingerprint);
constexpr int kUtimeEnd = kUtimeOffset + static_cast<int>(encoded_bytes::kInt64);

int64_t BigEndianInt64(const uint8_t* bytes) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | bytes[i];
  return static_cast<int64_t>(value);
}

double PositiveDouble(const Config& section, const std::string& key, double fallback) {
  const double value = section.GetDouble(key, fallback);
  if (!(value > 0.0)) section.FailKey(key, "must be positive");
  return value;
}

double NonNegativeDouble(const Config& section, const std::string& key, double fallback) {
  const double value = section.GetDouble(key, fallback);
  if (!(value >= 0.0)) section.FailKey(key, "must not be negative");
  return value;
}

double UnitInterval(const Config& section, const std::string& key, double fallback) {
  const double value = section.GetDouble(key, fallback);
  if (!(value >= 0.0 && value <= 1.0)) section.FailKey(key, "must be in [0, 1]");
  return value;
}

}  // namespace

SegmenterOptions ReadSegmenterOptions(const Config& section) {
  SegmenterOptions o;
  const double lambda_deg = section.GetDouble("lambda_deg", o.lambda_rad / kDegToRad);
  if (!(lambda_deg > 0.0 && lambda_deg < 90.0)) {
    section.FailKey("lambda_deg", "must be in (0, 90) degrees");
  }
  o.lambda_rad = lambda_deg * kDegToRad;
  o.sigma_r_m = PositiveDouble(section, "sigma_r_m", o.sigma_r_m);
  o.max_beam_gap_rad =
      PositiveDouble(section, "max_beam_gap_deg", o.max_beam_gap_rad / kDegToRad) * kDegToRad;
  const int64_t max_beams = section.GetInt("max_beams_per_scan", o.max_beams_per_scan);
  if (max_beams < 16 || max_beams > 10000000) {
    section.FailKey("max_beams_per_scan", "must be between 16 and 10000000");
  }
  o.max_beams_per_scan = static_cast<int>(max_beams);
  const int64_t max_dropped = section.GetInt("max_dropped_beams", o.max_dropped_beams);
  if (max_dropped < 0 || max_dropped > 100000) {
    section.FailKey("max_dropped_beams", "must be between 0 and 100000");
  }
  o.max_dropped_beams = static_cast<int>(max_dropped);
  const double duplicate_deg = NonNegativeDouble(section, "duplicate_angle_tolerance_deg",
                                                 o.duplicate_angle_tolerance_rad / kDegToRad);
  if (!(duplicate_deg < 0.5)) {
    section.FailKey("duplicate_angle_tolerance_deg", "must be below 0.5 degrees");
  }
  o.duplicate_angle_tolerance_rad = duplicate_deg * kDegToRad;
  o.min_range_m = NonNegativeDouble(section, "min_range_m", o.min_range_m);
  if (section.Has("max_range_m")) {
    o.max_range_m = section.GetDouble("max_range_m", 0.0);
    if (!(o.max_range_m > o.min_range_m)) {
      section.FailKey("max_range_m", "must be greater than min_range_m");
    }
  }
  const int64_t min_points = section.GetInt("min_points", o.min_points);
  if (min_points < 1 || min_points > 100000) {
    section.FailKey("min_points", "must be between 1 and 100000");
  }
  o.min_points = static_cast<int>(min_points);
  o.max_width_m = PositiveDouble(section, "max_width_m", o.max_width_m);
  const std::string rule = section.GetString("centre_rule", CentreRuleName(o.centre_rule));
  if (!ParseCentreRule(rule, &o.centre_rule)) {
    section.FailKey("centre_rule", "expected circle_fit, radius_corrected or middle_point, got '" +
                                       rule + "'");
  }
  const std::string classifier =
      section.GetString("leg_classifier", LegClassifierName(o.leg_classifier));
  if (!ParseLegClassifier(classifier, &o.leg_classifier)) {
    section.FailKey("leg_classifier", "expected trained or shape, got '" + classifier + "'");
  }
  o.max_object_radius_m = PositiveDouble(section, "max_object_radius_m", o.max_object_radius_m);
  o.bearing_sigma_rad =
      PositiveDouble(section, "bearing_sigma_deg", o.bearing_sigma_rad / kDegToRad) * kDegToRad;
  o.shape_sigma_fraction =
      NonNegativeDouble(section, "shape_sigma_fraction", o.shape_sigma_fraction);
  o.extract_lines = section.GetBool("extract_lines", o.extract_lines);
  o.line_split_distance_m =
      PositiveDouble(section, "line_split_distance_m", o.line_split_distance_m);
  o.line_split_range_fraction =
      NonNegativeDouble(section, "line_split_range_fraction", o.line_split_range_fraction);
  o.straight_piece_width_m =
      PositiveDouble(section, "straight_piece_width_m", o.straight_piece_width_m);
  const int64_t min_line_points = section.GetInt("min_line_points", o.min_line_points);
  if (min_line_points < 3 || min_line_points > 100000) {
    section.FailKey("min_line_points", "must be between 3 and 100000");
  }
  o.min_line_points = static_cast<int>(min_line_points);
  o.min_line_length_m = PositiveDouble(section, "min_line_length_m", o.min_line_length_m);
  o.leg.leg_min_diameter_m =
      PositiveDouble(section, "leg_min_diameter_m", o.leg.leg_min_diameter_m);
  o.leg.leg_max_diameter_m =
      PositiveDouble(section, "leg_max_diameter_m", o.leg.leg_max_diameter_m);
  o.leg.leg_diameter_margin_m =
      PositiveDouble(section, "leg_diameter_margin_m", o.leg.leg_diameter_margin_m);
  o.leg.convexity_floor = UnitInterval(section, "convexity_floor", o.leg.convexity_floor);
  o.detect_people = section.GetBool("detect_people", o.detect_people);
  o.leg_threshold = UnitInterval(section, "leg_threshold", o.leg_threshold);
  o.leg_nominal_diameter_m =
      PositiveDouble(section, "leg_nominal_diameter_m", o.leg_nominal_diameter_m);
  PersonDetectionOptions& p = o.person;
  p.min_leg_separation_m =
      NonNegativeDouble(section, "min_leg_separation_m", p.min_leg_separation_m);
  p.max_leg_separation_m =
      PositiveDouble(section, "max_leg_separation_m", p.max_leg_separation_m);
  p.single_leg_threshold = UnitInterval(section, "single_leg_threshold", p.single_leg_threshold);
  p.pair_centre_sigma_m = PositiveDouble(section, "pair_centre_sigma_m", p.pair_centre_sigma_m);
  p.single_leg_offset_sigma_m =
      PositiveDouble(section, "single_leg_offset_sigma_m", p.single_leg_offset_sigma_m);
  o.depth_edge_m = PositiveDouble(section, "depth_edge_m", o.depth_edge_m);
  section.CheckUnused();
  const std::string problem = CheckSegmenterOptions(o);
  if (!problem.empty()) section.Fail(problem);
  return o;
}

SegmenterStage::SegmenterStage(const SegmenterOptions& options, std::string laser_scan_channel,
                               std::string features_channel, std::string stage_timing_channel)
    : segmenter_(options),
      laser_scan_channel_(std::move(laser_scan_channel)),
      features_channel_(std::move(features_channel)),
      stage_timing_channel_(std::move(stage_timing_channel)) {}

SegmenterStage::SegmenterStage(const ProcessSettings& settings)
    : SegmenterStage(ReadSegmenterOptions(settings.config.Child("segmenter")),
                     settings.channels.Get("laser_scan"), settings.channels.Get("features"),
                     settings.channels.Get("stage_timing")) {}

void SegmenterStage::Reject(const std::string& reason) {
  ++counters_.scans_rejected;
  const int64_t n = counters_.scans_rejected;
  // 1st, 10th, 100th, ...: visible, but a flood of bad messages cannot flood the log.
  if (IsReportable(n)) {
    LogWarning() << "segmenter: rejected message on " << laser_scan_channel_ << ": " << reason
                 << " (" << n << " rejected so far)";
  }
}

void SegmenterStage::Handle(const std::string& channel, const void* data, int size,
                            MessageSink& out) {
  if (channel != laser_scan_channel_) return;
  if (data == nullptr || size < kUtimeEnd) {
    Reject("message of " + std::to_string(size) + " bytes is too short for a laser_scan_t");
    return;
  }
  StageTimer timer(Name(), BigEndianInt64(static_cast<const uint8_t*>(data) + kUtimeOffset));
  slammtt_msgs::laser_scan_t scan;
  // Decode checks the fingerprint and every array count against the size before LCM's decoder
  // runs (runtime/message_checks.h): a corrupt num_beams is a rejection, never an allocation.
  if (!Decode(data, size, &scan)) {
    Reject("not a well-formed laser_scan_t of " + std::to_string(size) +
           " bytes (type fingerprint, num_beams or size)");
    return;
  }
  timer.Lap("decode");

  ScanView view = MakeScanView(scan.angle_rad, scan.range_m, scan.valid);
  view.range_min_m = scan.range_min_m;
  view.range_max_m = scan.range_max_m;
  segmenter_.PrepareBeams(view);
  timer.Lap("sort");
  segmenter_.FindClusters();
  timer.Lap("cluster");
  segmenter_.ExtractLines();
  timer.Lap("lines");
  segmenter_.MakeFeatures();
  timer.Lap("features");
  const std::vector<Feature>& features = segmenter_.FindPeople();
  timer.Lap("people");

  slammtt_msgs::features_t message{};
  message.utime = scan.utime;
  message.sequence = scan.sequence;
  message.num_features = static_cast<int32_t>(features.size());
  message.features.reserve(features.size());
  for (const Feature& f : features) {
    slammtt_msgs::feature_t m{};
    m.range_m = f.range_m;
    m.bearing_rad = f.bearing_rad;
    m.width_m = f.width_m;
    m.num_points = f.num_points;
    m.range_var_m2 = f.covariance(0, 0);
    m.bearing_var_rad2 = f.covariance(1, 1);
    m.range_bearing_cov_m_rad = f.covariance(0, 1);
    m.leg_likeness = f.leg_likeness;
    message.features.push_back(m);
  }
  const std::vector<LineFeature>& lines = segmenter_.lines();
  message.num_lines = static_cast<int32_t>(lines.size());
  message.lines.reserve(lines.size());
  for (const LineFeature& l : lines) {
    slammtt_msgs::line_feature_t m{};
    m.rho_m = l.rho_m;
    m.alpha_rad = l.alpha_rad;
    m.rho_var_m2 = l.covariance(0, 0);
    m.alpha_var_rad2 = l.covariance(1, 1);
    m.rho_alpha_cov_m_rad = l.covariance(0, 1);
    m.first_x_m = l.first_point_m.x();
    m.first_y_m = l.first_point_m.y();
    m.last_x_m = l.last_point_m.x();
    m.last_y_m = l.last_point_m.y();
    m.num_points = l.num_points;
    m.rms_residual_m = l.rms_residual_m;
    message.lines.push_back(m);
  }
  const std::vector<PersonFeature>& people = segmenter_.people();
  message.num_people = static_cast<int32_t>(people.size());
  message.people.reserve(people.size());
  for (const PersonFeature& p : people) {
    slammtt_msgs::person_feature_t m{};
    m.range_m = p.range_m;
    m.bearing_rad = p.bearing_rad;
    m.range_var_m2 = p.covariance(0, 0);
    m.bearing_var_rad2 = p.covariance(1, 1);
    m.range_bearing_cov_m_rad = p.covariance(0, 1);
    m.num_legs = p.num_legs;
    m.leg_index[0] = p.leg_index[0];
    m.leg_index[1] = p.leg_index[1];
    m.confidence = p.confidence;
    message.people.push_back(m);
  }
  out.PublishMessage(features_channel_, message);
  timer.Lap("publish");

  const SegmentationStats& stats = segmenter_.stats();
  const int64_t dropped =
      stats.beams_flagged_invalid + stats.beams_non_finite + stats.beams_out_of_range;
  timer.Count("beams", stats.beams);
  timer.Count("beams_used", stats.beams_used);
  timer.Count("beams_over_cap", stats.beams_over_cap);
  timer.Count("beams_dropped", dropped);
  timer.Count("beams_duplicate", stats.beams_duplicate);
  timer.Count("clusters", stats.clusters);
  timer.Count("features", stats.features);
  timer.Count("circle_fit_fallbacks", stats.circle_fit_fallbacks);
  timer.Count("beams_mixed_pixel", stats.beams_mixed_pixel);
  timer.Count("beams_isolated", stats.beams_isolated);
  timer.Count("depth_edges", stats.depth_edges);
  timer.Count("lines", stats.lines);
  timer.Count("beams_on_lines", stats.beams_on_lines);
  timer.Count("clusters_on_lines", stats.clusters_on_lines);
  timer.Count("clusters_round", stats.clusters_round);
  timer.Count("clusters_structure_pieces", stats.clusters_structure_pieces);
  timer.Count("leg_candidates", stats.leg_candidates);
  timer.Count("provisional_legs_used", stats.provisional_legs_used);
  timer.Count("people", stats.people);
  timer.Count("people_one_leg", stats.people_one_leg);
  timer.Count("reversed", stats.beams_were_reversed ? 1 : 0);
  timer.Count("sorted", stats.beams_were_sorted ? 1 : 0);
  ++counters_.scans_handled;
  counters_.features_published += stats.features;
  counters_.beams_dropped += dropped;
  if (stats.beams_over_cap > 0) {
    const int64_t n = ++counters_.scans_over_beam_cap;
    if (IsReportable(n)) {
      LogWarning() << "segmenter: scan at utime " << scan.utime << " has " << stats.beams
                   << " beams, more than max_beams_per_scan ("
                   << segmenter_.options().max_beams_per_scan << "): " << stats.beams_over_cap
                   << " left out, every k-th kept (" << n << " such scans so far)";
    }
  }
  out.PublishMessage(stage_timing_channel_, timer.Finish());
}

std::unique_ptr<Stage> CreateSegmenterStage(const ProcessSettings& settings) {
  return std::make_unique<SegmenterStage>(settings);
}

}  // namespace slammtt
