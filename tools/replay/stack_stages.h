// The processing stages of the stack as replay runs them: created by the same factories as the
// live processes (perception/segmenter_stage.h, estimator/estimator_stage.h) from the same stack
// configuration, with the channels each one publishes.
#pragma once

#include <string>
#include <vector>

#include "runtime/process.h"
#include "tools/replay/log_replay.h"

namespace slammtt {

// "segmenter", "estimator": the names the `replay.stages` setting accepts, in pipeline order.
const std::vector<std::string>& StackStageNames();

// Whether the named stage is built into this program (both are, once both stage libraries
// exist; until then a default replay skips the missing one with a warning).
bool IsStackStageBuilt(const std::string& name);

// Creates the stages named in `enabled` (a subset of StackStageNames(), any order; they run in
// pipeline order). Each factory reads its own configuration section. Throws ConfigError for an
// unknown name, and std::runtime_error when a named stage is not built into this program.
std::vector<ReplayStage> CreateStackStages(const ProcessSettings& settings,
                                           const std::vector<std::string>& enabled);

}  // namespace slammtt
