#include "tools/replay/stack_stages.h"

#include <algorithm>

#include "estimator/estimator_stage.h"
#include "estimator/laser_geometry.h"
#include "perception/segmenter_stage.h"
#include "smoother/smoother_stage.h"

namespace slammtt {

const std::vector<std::string>& StackStageNames() {
  static const std::vector<std::string> names = {"segmenter", "estimator", "smoother"};
  return names;
}

std::vector<std::unique_ptr<Stage>> CreateStackStages(const ProcessSettings& settings,
                                                      const std::vector<std::string>& enabled) {
  for (const std::string& name : enabled) {
    if (std::find(StackStageNames().begin(), StackStageNames().end(), name) ==
        StackStageNames().end()) {
      throw ConfigError("replay.stages: unknown stage '" + name +
                        "' (known: segmenter, estimator, smoother)");
    }
  }
  auto wanted = [&](const std::string& name) {
    return std::find(enabled.begin(), enabled.end(), name) != enabled.end();
  };
  // Each stage declares what it publishes (Stage::OutputChannels): those channels of the input
  // are replaced by the recomputed ones.
  std::vector<std::unique_ptr<Stage>> stages;
  if (wanted("segmenter")) stages.push_back(CreateSegmenterStage(settings));
  if (wanted("estimator")) stages.push_back(CreateEstimatorStage(settings));
  if (wanted("smoother")) stages.push_back(CreateSmootherStage(settings));
  return stages;
}

std::vector<std::string> DefaultStackStages(const Config& config) {
  std::vector<std::string> stages = {"segmenter", "estimator"};
  if (config.Has("smoother")) stages.push_back("smoother");
  return stages;
}

std::string DefaultsLine(const LogScan& input, const Channels& channels,
                         const std::vector<std::string>& enabled) {
  std::string line = "no --config: every stage runs with its defaults";
  if (std::find(enabled.begin(), enabled.end(), "estimator") == enabled.end()) return line;
  const std::string& geometry_channel = channels.Get("laser_geometry");
  if (input.channels.count(geometry_channel) > 0) {
    return line + ", except the estimator's laser geometry: the log's " + geometry_channel +
           " gives it";
  }
  const EstimatorStageOptions defaults;
  return line + ", the estimator's laser geometry too (the log has no " + geometry_channel +
         "): " + DescribeLaserGeometry(LaserGeometryOf(defaults.estimator)) +
         "; give the sensor's with --config (docs/estimator.md, \"Laser geometry\")";
}

}  // namespace slammtt
