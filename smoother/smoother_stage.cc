#include "smoother/smoother_stage.h"

#include "common/angle.h"
#include "estimator/row_major.h"
#include "estimator/smoother_input_message.h"
#include "runtime/config_options.h"
#include "runtime/log.h"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/smoother_input_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/trajectory_t.hpp"

namespace slammtt {

KeyframeSmootherOptions ReadSmootherOptions(const Config& section) {
  KeyframeSmootherOptions options;
  ConfigOptionReader reader(section);
  VisitKeyframeSmootherOptions(&reader, &options);
  section.CheckUnused();
  const std::string problem = CheckKeyframeSmootherOptions(options);
  if (!problem.empty()) section.Fail(problem);
  return options;
}

std::string SmootherOptionsTable() {
  KeyframeSmootherOptions defaults;
  OptionsMarkdownTable table;
  VisitKeyframeSmootherOptions(&table, &defaults);
  return table.Table();
}

SmootherStage::SmootherStage(const KeyframeSmootherOptions& options, const Channels& channels)
    : smoother_(options),
      map_every_keyframes_(options.map_every_keyframes),
      input_channel_(channels.Get("smoother_input")),
      pose_channel_(channels.Get("smoothed_pose")),
      map_channel_(channels.Get("smoothed_map")),
      trajectory_channel_(channels.Get("smoothed_trajectory")),
      timing_channel_(channels.Get("stage_timing")) {}

SmootherStage::SmootherStage(const ProcessSettings& settings)
    : SmootherStage(ReadSmootherOptions(settings.config.Child("smoother")), settings.channels) {}

void SmootherStage::Handle(const std::string& channel, const void* data, int size,
                           MessageSink& out) {
  if (channel != input_channel_) return;
  slammtt_msgs::smoother_input_t message;
  if (!Decode(data, size, &message)) {
    const int64_t n = ++counters_.messages_undecodable;
    if (IsReportable(n)) {
      LogWarning() << "smoother: undecodable smoother_input_t message dropped (" << n
                   << " so far)";
    }
    return;
  }
  StageTimer timer("smoother", message.utime);
  const SmootherScanInput input = SmootherScanInputFromMessage(message);
  const int64_t refused_before = smoother_.counters().inputs_refused;
  const SmoothedScan scan = smoother_.AddScan(input);
  timer.Lap("smooth");
  if (!scan.processed) return;
  const int64_t refused = smoother_.counters().inputs_refused - refused_before;
  if (refused > 0 && IsReportable(smoother_.counters().inputs_refused)) {
    LogWarning() << "smoother: scan at utime " << message.utime << ": " << refused
                 << " input(s) refused, last: " << smoother_.last_error() << " ("
                 << smoother_.counters().inputs_refused << " so far)";
  }

  slammtt_msgs::pose_t pose;
  pose.utime = message.utime;
  pose.x_m = scan.pose(0);
  pose.y_m = scan.pose(1);
  pose.heading_rad = scan.pose(2);
  WriteRowMajor<3>(scan.pose_covariance, pose.covariance);
  out.PublishMessage(pose_channel_, pose);
  if (scan.keyframe && ++keyframes_since_map_ >= map_every_keyframes_) {
    keyframes_since_map_ = 0;
    PublishMap(message.utime, out);
    PublishTrajectory(message.utime, out);
  }
  timer.Lap("publish");
  timer.Count("observations", static_cast<int64_t>(input.observations.size()));
  timer.Count("keyframe", scan.keyframe ? 1 : 0);
  timer.Count("keyframes", smoother_.counters().keyframes);
  timer.Count("landmarks", smoother_.smoother() ? smoother_.smoother()->num_landmarks() : 0);
  timer.Count("refactorized", scan.update.refactorized ? 1 : 0);
  timer.Count("batch", scan.batch ? 1 : 0);
  timer.Count("refused", refused);
  out.PublishMessage(timing_channel_, timer.Finish());
  ++counters_.scans_published;
}

void SmootherStage::PublishMap(int64_t utime, MessageSink& out) {
  slammtt_msgs::map_t map;
  map.utime = utime;
  for (const SmoothedLandmark& l : smoother_.Landmarks()) {
    slammtt_msgs::landmark_t landmark;
    landmark.id = l.id;
    landmark.x_m = l.position(0);
    landmark.y_m = l.position(1);
    WriteRowMajor<2>(l.covariance, landmark.covariance);
    map.landmarks.push_back(landmark);
  }
  map.num_landmarks = static_cast<int32_t>(map.landmarks.size());
  map.num_lines = 0;
  out.PublishMessage(map_channel_, map);
}

void SmootherStage::PublishTrajectory(int64_t utime, MessageSink& out) {
  slammtt_msgs::trajectory_t trajectory;
  trajectory.utime = utime;
  for (const auto& [keyframe_utime, pose] : smoother_.Keyframes()) {
    trajectory.pose_utime.push_back(keyframe_utime);
    trajectory.x_m.push_back(pose(0));
    trajectory.y_m.push_back(pose(1));
    trajectory.heading_rad.push_back(WrapAngle(pose(2)));
  }
  trajectory.num_poses = static_cast<int32_t>(trajectory.pose_utime.size());
  out.PublishMessage(trajectory_channel_, trajectory);
}

std::unique_ptr<Stage> CreateSmootherStage(const ProcessSettings& settings) {
  return std::make_unique<SmootherStage>(settings);
}

}  // namespace slammtt
