#include "tools/replay/replay_config.h"

#include "runtime/config_options.h"

namespace slammtt {

void VisitReplayFileOptions(OptionVisitor* v, ReplayFileOptions* o) {
  using R = OptionRange;
  v->Int("progress_every_events", &o->progress_every_events, R::AtLeast(1),
         "a progress line every this many events...");
  // Below a microsecond or beyond 30 years a progress step means nothing.
  v->Double("progress_every_log_s", &o->progress_every_log_s, R::Between(1e-6, 1e9),
            "...or this many seconds of log time, whichever comes first; a log whose timestamps "
            "jump or run backwards still gets one line per step reached");
  // The key names the choice; the field says whether it is `error`.
  int truncated_tail = o->truncated_tail_is_error ? 1 : 0;
  v->Choice("truncated_tail", &truncated_tail, {"warn", "error"},
            "a truncated final event: a warning, or an error (as `--strict`)");
  o->truncated_tail_is_error = truncated_tail == 1;
}

std::string ReplayOptionsTable() {
  ReplayFileOptions defaults;
  OptionsMarkdownTable table;
  VisitReplayFileOptions(&table, &defaults);
  return table.Table();
}

ReplaySettings ReadReplaySettings(const Config& section,
                                  const std::vector<std::string>& default_stages) {
  ReplaySettings settings;
  settings.stages = default_stages;
  if (section.Has("stages")) {
    settings.stages.clear();
    for (const Config& item : section.Items("stages")) settings.stages.push_back(item.AsString());
  }
  ConfigOptionReader reader(section);
  VisitReplayFileOptions(&reader, &settings.file_options);
  section.CheckUnused();
  return settings;
}

}  // namespace slammtt
