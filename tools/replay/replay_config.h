// The `replay:` section of the stack configuration, read for slammtt-replay (docs/tools.md):
//   stages                 [segmenter, estimator]  stages that may run (pipeline order; and
//                                                  smoother with a `smoother:` section)
//   progress_every_events  20000                   a progress line every this many events...
//   progress_every_log_s   30                      ...or this many seconds of log time
//   truncated_tail         warn                    warn | error (as --strict)
// Unknown keys and bad values are ConfigErrors naming file, line and key.
#pragma once

#include <string>
#include <vector>

#include "runtime/config.h"
#include "tools/replay/log_replay.h"

namespace slammtt {

struct ReplaySettings {
  std::vector<std::string> stages;  // names; checked against the stack's by CreateStackStages()
  ReplayFileOptions file_options;   // progress and truncation settings (no paths, no channel)
};

// `default_stages`: the stages when the section names none (StackStageNames()).
ReplaySettings ReadReplaySettings(const Config& section,
                                  const std::vector<std::string>& default_stages);

}  // namespace slammtt
