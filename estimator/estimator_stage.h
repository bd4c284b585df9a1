// The estimator as a processing stage (runtime/stage.h): ODOMETRY, FEATURES and LASER_GEOMETRY
// in; POSE, MAP, TRACKS, SMOOTHER_INPUT, ESTIMATOR_STATUS and STAGE_TIMING out. The live process
// (slammtt-estimator) and slammtt-replay run this same object; it depends on nothing live (no
// clock except StageTimer's durations, no LCM handle), and its RANSAC generator is seeded from
// the configuration, so a replay gives the same bytes every time.
//
// Per odometry_t: buffered for the next scan (Estimator::AddOdometry). Nothing is published,
// except an estimator_status_t (with the odometry's utime) when the message is dropped.
// Per features_t: one step of Algorithm 2 (Estimator::ProcessScan), then, all with the FEATURES
// message's utime and in this order:
//  - pose_t (`pose`): robot pose in the map frame (the start pose) and its covariance;
//  - map_t (`map`): every confirmed STATIC object that is not a person (a standing person), and
//    every line landmark (walls);
//  - tracks_t (`tracks`): every object, with its class (STATIC / MOVING / UNDECIDED), its kind
//    (PERSON / OTHER), whether it is confirmed, measured in this scan, how long it has coasted
//    and whether it is a reported track (track_management.h);
//  - smoother_input_t (`smoother_input`): the scan's motion and static associations for the
//    smoother (smoother_input.h, docs/smoother.md);
//  - estimator_status_t (`estimator_status`): cumulative counters and the last unusual event;
//  - stage_timing_t (`stage_timing`): stage "estimator", substages "predict", "gating",
//    "level1", "ransac", "level2_3", "track_management"; counters "features" (received),
//    "objects" (after the scan), "hypotheses" (RANSAC hypotheses of this scan), "updates",
//    "updates_skipped", "lines" (line features received), "line_updates", "new_lines".
// Per pose_t on SMOOTHED_POSE and map_t on SMOOTHED_MAP (only with the estimator's
// smoother_feedback: then they are input channels): the smoother's estimate moves the filter's
// pose and static landmarks (smoother_feedback.h); nothing is published.
// Per laser_geometry_t: the parts of the laser geometry the configuration does not give are
// taken from it, and the parts it gives are compared with it (laser_geometry.h); nothing is
// published. Each geometry the log gives is reported once, in one line on stderr: what was
// taken (an info line naming the values), or what disagrees (a warning naming both values;
// counted in counters().geometry_disagreements). An unusable geometry is counted
// (geometry_rejected), warned about once and not used.
// A scan older than the last processed one is dropped: only estimator_status_t is published.
// A message that cannot be decoded is counted (counters().messages_undecodable), logged (the
// 1st, 10th, 100th, ... time) and nothing is published: it has no trustworthy utime.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/laser_geometry.h"
#include "estimator/smoother_input.h"
#include "runtime/config.h"
#include "runtime/config_options.h"
#include "runtime/process.h"
#include "runtime/stage.h"
#include "slammtt_msgs/features_t.hpp"

namespace slammtt {

struct EstimatorStageOptions {
  EstimatorOptions estimator;
  uint64_t seed = 1;  // estimator.seed: seeds the RANSAC generator
  // estimator.person_features: a person feature of FEATURES becomes one measurement (its
  // centre and covariance) in place of the point features of its legs, so that a person on two
  // legs is one object to track, not two. false: every point feature is a measurement and
  // person features are ignored. Line features update the line landmarks (line_landmarks.h).
  bool person_features = true;
  // The parts of the laser geometry the section gives (any of their keys present): kept and
  // compared with a log's LASER_GEOMETRY; the others are taken from it. Not an option: set by
  // ReadEstimatorOptions from the keys present.
  ConfiguredGeometryParts geometry_given;
};

// The measurements of one FEATURES message (EstimatorStageOptions::person_features). A person
// measurement's width is the span of its legs (the distance between their centres plus their
// mean width; one leg: its width). A leg_index out of range or naming a leg of another person
// is ignored (the index, not the person). Pure: exposed for tests.
ScanInput ScanInputFromFeatures(const slammtt_msgs::features_t& message, bool person_features);

// The schema of the `estimator:` section (common/options_schema.h): the stage's own options
// (seed, person_features), then the estimator's (VisitEstimatorOptions, estimator_options.h).
void VisitEstimatorStageOptions(OptionVisitor* visitor, EstimatorStageOptions* options);

// Keys of earlier versions of the `estimator:` section and their new names (the migration
// note of docs/estimator.md lists the same).
const std::vector<RenamedKey>& RenamedEstimatorKeys();

// Reads the `estimator:` section of the stack configuration through the schema; absent keys
// keep the defaults of EstimatorStageOptions, and geometry_given says which geometry keys are
// present. Throws ConfigError naming file, line and key for a
// renamed key (with its new name), a wrong type, a value out of its range, an unknown key
// (CheckUnused()) or options that do not fit together (CheckEstimatorOptions).
EstimatorStageOptions ReadEstimatorOptions(const Config& section);

// The Markdown table of every key of the `estimator:` section (docs/estimator.md, "Options";
// printed by slammtt-estimator --options-table).
std::string EstimatorStageOptionsTable();

struct EstimatorStageCounters {
  int64_t scans_published = 0;
  int64_t messages_undecodable = 0;
  int64_t geometry_messages = 0;       // LASER_GEOMETRY messages decoded
  int64_t geometry_disagreements = 0;  // geometries that disagree with the configuration
  int64_t geometry_rejected = 0;       // geometries not used (unusable values)
};

class EstimatorStage : public Stage {
 public:
  EstimatorStage(const EstimatorStageOptions& options, const Channels& channels);
  // Options from settings.config's `estimator:` section, channels from settings.channels.
  explicit EstimatorStage(const ProcessSettings& settings);

  std::string Name() const override { return "estimator"; }
  std::vector<std::string> InputChannels() const override;
  std::vector<std::string> OutputChannels() const override;
  void Handle(const std::string& channel, const void* data, int size, MessageSink& out) override;

  const Estimator& estimator() const { return estimator_; }
  const EstimatorStageCounters& counters() const { return counters_; }

 private:
  void HandleOdometry(const void* data, int size, MessageSink& out);
  void HandleFeatures(const void* data, int size, MessageSink& out);
  void HandleLaserGeometry(const void* data, int size);
  // With smoother_feedback: SMOOTHED_POSE is kept; the SMOOTHED_MAP of the same utime then
  // moves the filter to the smoother's estimate (Estimator::ApplySmoothedEstimate). Nothing is
  // published: the next scan's POSE and MAP carry the correction.
  void HandleSmoothedPose(const void* data, int size);
  void HandleSmoothedMap(const void* data, int size);
  void PublishStatus(int64_t utime, MessageSink& out);
  void PublishSmootherInput(const ScanResult& result, MessageSink& out);
  void Undecodable(const std::string& what);

  Estimator estimator_;
  std::mt19937_64 rng_;
  bool person_features_;
  // The options as configured and the geometry parts they give: every log geometry is
  // reconciled against these, not against a geometry an earlier message gave.
  EstimatorOptions configured_;
  ConfiguredGeometryParts geometry_given_;
  std::optional<std::array<double, 6>> log_geometry_;  // the last one reconciled, its values
  std::string odometry_channel_;
  std::string features_channel_;
  std::string laser_geometry_channel_;
  std::string pose_channel_;
  std::string map_channel_;
  std::string tracks_channel_;
  std::string smoother_input_channel_;
  bool smoother_feedback_;
  std::string smoothed_pose_channel_;
  std::string smoothed_map_channel_;
  std::optional<std::pair<int64_t, Eigen::Vector3d>> smoothed_pose_;  // the last SMOOTHED_POSE
  std::string status_channel_;
  std::string timing_channel_;
  EstimatorStageCounters counters_;
  SmootherInputBuilder smoother_input_;
};

// The factory slammtt-replay and slammtt-estimator use.
std::unique_ptr<Stage> CreateEstimatorStage(const ProcessSettings& settings);

}  // namespace slammtt
