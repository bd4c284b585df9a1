// Scenario files: YAML read through runtime/config.h (docs/world.md lists every key). Every
// error is one line naming the file, the line and the key:
//   config/scenarios/s2-lobby.yaml:41: movers[3].radius_m: must be positive, got -0.3
// Unknown keys are errors (Config::CheckUnused), values are range-checked, and the whole
// scenario, including referenced trajectory files, is read and checked before anything runs.
// Paths inside a scenario (crowd.file) are relative to the scenario file's folder.
#pragma once

#include <string>
#include <vector>

#include "runtime/config.h"
#include "tools/world/recorded_crowd.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Loads and validates a scenario file; ConfigError on any problem.
Scenario LoadScenario(const std::string& path);
// The same from YAML text; `source` names it in errors, `base_dir` resolves relative file paths.
Scenario LoadScenarioFromString(const std::string& yaml_text, const std::string& source,
                                const std::string& base_dir);

// Reads a recorded-trajectory file: tab-separated, header line "t_s id x_m y_m", rows sorted by
// time. ConfigError "PATH:LINE: ..." for a missing file, a malformed row, a person id beyond
// +-1e15 or a person whose times do not increase.
std::vector<RecordedTrack> ReadRecordedTracks(const std::string& path);

// The scenario file for --scenario: a NAME (no '/' and no ".yaml") is looked up as
// config/scenarios/NAME.yaml in `search_roots`, in order; anything else is a path. ConfigError
// listing the places tried when nothing is found.
std::string ResolveScenarioPath(const std::string& name_or_path,
                                const std::vector<std::string>& search_roots);

// Where a program looks --scenario NAME up: `source_dir` (the source tree it was built from),
// then the tree around the executable (build/bin/ -> ../../, then ../), without repeats.
std::vector<std::string> ScenarioSearchRoots(const std::string& source_dir);

}  // namespace slammtt
