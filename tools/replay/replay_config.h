// The `replay:` section of the stack configuration, read for slammtt-replay (docs/tools.md):
// `stages` (the list of stages that may run, [segmenter, estimator] by default: pipeline order;
// and smoother with a `smoother:` section) and the settings of VisitReplayFileOptions.
// Unknown keys and bad values are ConfigErrors naming file, line and key.
#pragma once

#include <string>
#include <vector>

#include "common/options_schema.h"
#include "runtime/config.h"
#include "tools/replay/log_replay.h"

namespace slammtt {

struct ReplaySettings {
  std::vector<std::string> stages;  // names; checked against the stack's by CreateStackStages()
  ReplayFileOptions file_options;   // progress and truncation settings (no paths, no channel)
};

// The options schema of the replay's settings: progress_every_events, progress_every_log_s and
// truncated_tail (warn or error: ReplayFileOptions::truncated_tail_is_error, as --strict). The
// reader and the table of docs/tools.md (slammtt-replay --options-table) come from it.
void VisitReplayFileOptions(OptionVisitor* visitor, ReplayFileOptions* options);
std::string ReplayOptionsTable();

// `default_stages`: the stages when the section names none (StackStageNames()).
ReplaySettings ReadReplaySettings(const Config& section,
                                  const std::vector<std::string>& default_stages);

}  // namespace slammtt
