// The smoother as a processing stage (runtime/stage.h): SMOOTHER_INPUT in (the estimator's
// smoother_input_t, one per scan); SMOOTHED_POSE, SMOOTHED_MAP and STAGE_TIMING out. The live
// process (slammtt-smoother) and slammtt-replay run this same object; nothing in it is live
// (no clock except StageTimer's durations, no LCM handle), so a replay gives the same bytes
// every time. The work is in KeyframeSmoother (keyframe_smoother.h).
//
// Per smoother_input_t, all with its utime and in this order:
//  - pose_t (`smoothed_pose`): the robot at the scan, map frame of the estimator: the last
//    keyframe's smoothed estimate composed with the odometry since, and its covariance (zero
//    with covariances: false);
//  - map_t (`smoothed_map`), at every map_every_keyframes-th keyframe: every landmark of the
//    problem at its smoothed estimate, ids as the estimator's, with its marginal covariance; no
//    lines;
//  - trajectory_t (`smoothed_trajectory`), right after each map: every keyframe of the problem
//    (since the last start) at its current smoothed estimate, each at its scan's utime. This is
//    the smoothed trajectory in the smoothing sense (each pose estimated from every measurement
//    so far, later ones included), where smoothed_pose is what the smoother knew at the scan;
//  - stage_timing_t (`stage_timing`): stage "smoother", substages "smooth" (the scan's variables
//    and factors, Update, and Optimize when due) and "publish" (covariances and messages);
//    counters "observations", "keyframe" (1 or 0), "keyframes", "landmarks",
//    "refactorized", "batch" (1 when a batch solve ran), "refused".
// An undecodable message is counted and logged (1st, 10th, 100th, ...), and nothing is
// published; a scan not newer than the last is dropped (counted; nothing published).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/config.h"
#include "runtime/process.h"
#include "runtime/stage.h"
#include "smoother/keyframe_smoother.h"

namespace slammtt {

// Reads the `smoother:` section through the schema (VisitKeyframeSmootherOptions); absent keys
// keep the defaults. Throws ConfigError naming file, line and key for a wrong type, a value out
// of range or an unknown key.
KeyframeSmootherOptions ReadSmootherOptions(const Config& section);

// The Markdown table of every key of the `smoother:` section (docs/smoother.md; printed by
// slammtt-smoother --options-table).
std::string SmootherOptionsTable();

struct SmootherStageCounters {
  int64_t scans_published = 0;
  int64_t messages_undecodable = 0;
};

class SmootherStage : public Stage {
 public:
  SmootherStage(const KeyframeSmootherOptions& options, const Channels& channels);
  // Options from settings.config's `smoother:` section, channels from settings.channels.
  explicit SmootherStage(const ProcessSettings& settings);

  std::string Name() const override { return "smoother"; }
  std::vector<std::string> InputChannels() const override { return {input_channel_}; }
  std::vector<std::string> OutputChannels() const override { return {pose_channel_, map_channel_, trajectory_channel_}; }
  void Handle(const std::string& channel, const void* data, int size, MessageSink& out) override;

  const KeyframeSmoother& smoother() const { return smoother_; }
  const SmootherStageCounters& counters() const { return counters_; }

 private:
  void PublishMap(int64_t utime, MessageSink& out);
  void PublishTrajectory(int64_t utime, MessageSink& out);

  KeyframeSmoother smoother_;
  int map_every_keyframes_;
  int keyframes_since_map_ = 0;
  std::string input_channel_;
  std::string pose_channel_;
  std::string map_channel_;
  std::string trajectory_channel_;
  std::string timing_channel_;
  SmootherStageCounters counters_;
};

// The factory slammtt-replay and slammtt-smoother use.
std::unique_ptr<Stage> CreateSmootherStage(const ProcessSettings& settings);

}  // namespace slammtt
