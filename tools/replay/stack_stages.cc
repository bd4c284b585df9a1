#include "tools/replay/stack_stages.h"

#include <algorithm>
#include <stdexcept>

#if SLAMMTT_HAVE_SEGMENTER_STAGE
#include "perception/segmenter_stage.h"
#endif
#if SLAMMTT_HAVE_ESTIMATOR_STAGE
#include "estimator/estimator_stage.h"
#endif

namespace slammtt {

const std::vector<std::string>& StackStageNames() {
  static const std::vector<std::string> names = {"segmenter", "estimator"};
  return names;
}

bool IsStackStageBuilt(const std::string& name) {
  if (name == "segmenter") return SLAMMTT_HAVE_SEGMENTER_STAGE != 0;
  if (name == "estimator") return SLAMMTT_HAVE_ESTIMATOR_STAGE != 0;
  return false;
}

std::vector<ReplayStage> CreateStackStages(const ProcessSettings& settings,
                                           const std::vector<std::string>& enabled) {
  for (const std::string& name : enabled) {
    if (std::find(StackStageNames().begin(), StackStageNames().end(), name) ==
        StackStageNames().end()) {
      throw ConfigError("replay.stages: unknown stage '" + name +
                        "' (known: segmenter, estimator)");
    }
  }
  auto wanted = [&](const std::string& name) {
    return std::find(enabled.begin(), enabled.end(), name) != enabled.end();
  };
  const Channels& channels = settings.channels;
  std::vector<ReplayStage> stages;
  if (wanted("segmenter")) {
#if SLAMMTT_HAVE_SEGMENTER_STAGE
    stages.push_back(ReplayStage{CreateSegmenterStage(settings), {channels.Get("features")}});
#else
    throw std::runtime_error("the segmenter stage is not built into this program");
#endif
  }
  if (wanted("estimator")) {
#if SLAMMTT_HAVE_ESTIMATOR_STAGE
    stages.push_back(ReplayStage{CreateEstimatorStage(settings),
                                 {channels.Get("pose"), channels.Get("map"),
                                  channels.Get("tracks"), channels.Get("estimator_status")}});
#else
    throw std::runtime_error("the estimator stage is not built into this program");
#endif
  }
  (void)channels;
  return stages;
}

}  // namespace slammtt
