#include "perception/segmenter_stage.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include "runtime/config_options.h"
#include "runtime/lcm_io.h"
#include "runtime/log.h"
#include "runtime/message_checks.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"

namespace slammtt {
namespace {

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

}  // namespace

const std::vector<RenamedKey>& RenamedSegmenterKeys() {
  static const std::vector<RenamedKey> renamed = {
      {"convexity_floor", "leg_convexity_floor"},
      {"min_leg_separation_m", "person_min_leg_separation_m"},
      {"max_leg_separation_m", "person_max_leg_separation_m"},
      {"single_leg_threshold", "person_single_leg_threshold"},
      {"pair_centre_sigma_m", "person_pair_centre_sigma_m"},
      {"single_leg_offset_sigma_m", "person_single_leg_offset_sigma_m"},
  };
  return renamed;
}

SegmenterOptions ReadSegmenterOptions(const Config& section) {
  RejectRenamedKeys(section, RenamedSegmenterKeys(), "docs/perception.md, \"Migration\"");
  SegmenterOptions o;
  ConfigOptionReader reader(section);
  VisitSegmenterOptions(&reader, &o);
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
