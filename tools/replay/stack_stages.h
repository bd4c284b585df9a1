// The processing stages of the stack as replay runs them: created by the same factories as the
// live processes (perception/segmenter_stage.h, estimator/estimator_stage.h,
// smoother/smoother_stage.h) from the same stack
// configuration; each declares the channels it publishes (Stage::OutputChannels).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "runtime/log_scan.h"
#include "runtime/process.h"
#include "runtime/stage.h"
#include "tools/replay/log_replay.h"

namespace slammtt {

// "segmenter", "estimator", "smoother": the names the `replay.stages` setting accepts, in pipeline order.
const std::vector<std::string>& StackStageNames();

// The stages a replay runs when neither replay.stages nor --stage names them: the segmenter and
// the estimator, and the smoother when the configuration has a `smoother:` section.
std::vector<std::string> DefaultStackStages(const Config& config);

// Creates the stages named in `enabled` (a subset of StackStageNames(), any order; they run in
// pipeline order). Each factory reads its own configuration section and rejects unknown keys.
// Throws ConfigError for an unknown stage name.
std::vector<std::unique_ptr<Stage>> CreateStackStages(const ProcessSettings& settings,
                                                      const std::vector<std::string>& enabled);

// The line slammtt-replay prints when it runs without --config: that every stage runs with its
// defaults, and where the estimator's laser geometry comes from: the log's LASER_GEOMETRY
// (`input` has that channel) or the estimator's defaults, named with their values.
std::string DefaultsLine(const LogScan& input, const Channels& channels,
                         const std::vector<std::string>& enabled);

}  // namespace slammtt
