#include "tools/replay/replay_config.h"

#include <cmath>

namespace slammtt {

ReplaySettings ReadReplaySettings(const Config& section,
                                  const std::vector<std::string>& default_stages) {
  ReplaySettings settings;
  settings.stages = default_stages;
  if (section.Has("stages")) {
    settings.stages.clear();
    for (const Config& item : section.Items("stages")) settings.stages.push_back(item.AsString());
  }
  ReplayFileOptions& options = settings.file_options;
  options.progress_every_events =
      section.GetInt("progress_every_events", options.progress_every_events);
  if (options.progress_every_events < 1) {
    section.FailKey("progress_every_events", "must be at least 1");
  }
  options.progress_every_log_s =
      section.GetDouble("progress_every_log_s", options.progress_every_log_s);
  // Below a microsecond or beyond 30 years a progress step means nothing.
  if (!(options.progress_every_log_s >= 1e-6 && options.progress_every_log_s <= 1e9)) {
    section.FailKey("progress_every_log_s", "must be between 1e-6 and 1e9 seconds");
  }
  const std::string tail = section.GetString("truncated_tail", "warn");
  if (tail != "warn" && tail != "error") {
    section.FailKey("truncated_tail", "expected warn or error, got \"" + tail + "\"");
  }
  options.truncated_tail_is_error = tail == "error";
  section.CheckUnused();
  return settings;
}

}  // namespace slammtt
