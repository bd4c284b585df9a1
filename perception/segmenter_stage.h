// The segmenter as a processing stage (runtime/stage.h): LASER_SCAN in, FEATURES and
// STAGE_TIMING out. The live process (slammtt-segmenter) and slammtt-replay run this same object;
// it depends on nothing live (no clock except StageTimer's durations, no LCM handle).
//
// Per laser_scan_t message it publishes, in this order:
//  - features_t on the `features` channel: the scan's utime and sequence, one feature_t per
//    Feature (range, bearing, width, points, covariance, leg-likeness), one line_feature_t per
//    LineFeature, one person_feature_t per PersonFeature (leg_index into the features); empty
//    lists when nothing was found.
//  - stage_timing_t on the `stage_timing` channel: stage "segmenter", substages "decode",
//    "sort" (filter, order, duplicates), "cluster" (eq. 15), "lines", "features" (centres,
//    covariance, leg-likeness), "people", "publish"; counters "beams", "beams_used",
//    "beams_over_cap" (beyond max_beams_per_scan, left out; also on stderr, 1st, 10th, ...
//    such scan), "beams_dropped" (invalid, non-finite, out of range), "beams_duplicate",
//    "clusters",
//    "features", "circle_fit_fallbacks", "beams_mixed_pixel", "beams_isolated", "depth_edges",
//    "lines", "beams_on_lines", "clusters_on_lines", "clusters_round",
//    "clusters_structure_pieces", "leg_candidates", "provisional_legs_used", "people",
//    "people_one_leg", "reversed" (1 for a clockwise scan), "sorted" (1 when the beams were in
//    no circular order).
// A message that is not a laser_scan_t, or whose size does not match its num_beams, is counted
// (counters().scans_rejected) and reported on stderr (the 1st, 10th, 100th, ... time), and
// nothing is published for it: there is no trustworthy utime to publish with.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "perception/segmenter.h"
#include "perception/segmenter_options.h"
#include "runtime/config.h"
#include "runtime/config_options.h"
#include "runtime/process.h"
#include "runtime/stage.h"

namespace slammtt {

// Keys of earlier versions of the `segmenter:` section and their new names (the migration
// note of docs/perception.md lists the same).
const std::vector<RenamedKey>& RenamedSegmenterKeys();

// Reads the `segmenter:` section of the stack configuration through the schema
// (VisitSegmenterOptions, segmenter_options.h; the keys are in docs/perception.md, "Options",
// and slammtt-segmenter --options-table prints them); absent keys keep the defaults of
// SegmenterOptions. Throws ConfigError naming file, line and key for a renamed key (with its
// new name), a wrong type, a value out of its range, an unknown key (CheckUnused()) or options
// that do not fit together (CheckSegmenterOptions).
SegmenterOptions ReadSegmenterOptions(const Config& section);

struct SegmenterStageCounters {
  int64_t scans_handled = 0;   // scans segmented and published
  int64_t scans_rejected = 0;  // undecodable or inconsistent messages
  int64_t features_published = 0;
  int64_t beams_dropped = 0;   // invalid, non-finite or out of range, over all scans
  int64_t scans_over_beam_cap = 0;  // scans with more than max_beams_per_scan beams
};

class SegmenterStage : public Stage {
 public:
  SegmenterStage(const SegmenterOptions& options, std::string laser_scan_channel,
                 std::string features_channel, std::string stage_timing_channel);
  // Options from settings.config's `segmenter:` section, channels from settings.channels.
  explicit SegmenterStage(const ProcessSettings& settings);

  std::string Name() const override { return "segmenter"; }
  std::vector<std::string> InputChannels() const override { return {laser_scan_channel_}; }
  std::vector<std::string> OutputChannels() const override { return {features_channel_}; }
  void Handle(const std::string& channel, const void* data, int size, MessageSink& out) override;

  const SegmenterStageCounters& counters() const { return counters_; }
  const Segmenter& segmenter() const { return segmenter_; }

 private:
  void Reject(const std::string& reason);

  Segmenter segmenter_;
  std::string laser_scan_channel_;
  std::string features_channel_;
  std::string stage_timing_channel_;
  SegmenterStageCounters counters_;
};

// The factory slammtt-replay and slammtt-segmenter use.
std::unique_ptr<Stage> CreateSegmenterStage(const ProcessSettings& settings);

}  // namespace slammtt
