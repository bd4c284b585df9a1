// Reads the channels slammtt-eval needs from an LCM log into EvalInput: GROUND_TRUTH, ODOMETRY,
// POSE, TRACKS and MAP (channel names from the stack's Channels). A message that cannot be
// decoded, holds a non-finite number or one beyond 1e6 (metres, m/s, covariance entries), a
// utime outside [0, 1e18] us, an unknown class, a negative beams_on_object, duplicate object ids,
// or repeats the utime of an earlier one of its channel is rejected and counted
// (EvalInput::rejected), never used; messages are sorted by utime per channel (a live recording
// may interleave them). LASER_SCAN messages are only counted (EvalInput::laser_scans).
// A person's legs (KIND_LEG) are folded into their person (eval_input.h); a leg whose person is
// not in the same message, an unknown kind or a wall kind on a compact object rejects the
// GROUND_TRUTH message. The straight static surfaces come from the first accepted message.
//
// Also the rest of slammtt-eval's contact with files and configuration: the `eval:` section and
// writing the report and the pictures.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "runtime/channels.h"
#include "runtime/command_line.h"
#include "runtime/config.h"
#include "tools/eval/eval_input.h"
#include "tools/eval/evaluation.h"
#include "runtime/log_reader.h"

namespace slammtt {

// Throws std::runtime_error when the log cannot be opened. `read` receives the damage report.
EvalInput ReadEvalInput(const std::string& path, const Channels& channels, LogReadResult* read);

// The `eval:` section (docs/evaluation.md, "Options"), through the schema (VisitEvalOptions,
// evaluation.h): absent keys keep the defaults. ConfigError naming file, line and key for an
// unknown key or a value outside the range Evaluate() accepts.
EvalOptions ReadEvalOptions(const Config& section);

// The options of slammtt-eval from a whole-stack configuration: its `eval:` section
// (ReadEvalOptions), except that when that section does not set min_beams and the stack sets
// segmenter.min_points, min_beams follows it: one number says how many beams make an object
// (the segmenter makes no feature from fewer points, so the scoring must not expect one).
// ConfigError naming segmenter.min_points for a value outside [1, kMaxMinBeams].
EvalOptions ReadStackEvalOptions(const Config& stack);

// Declares --min-beams, --min-moving-speed-mps and --match-threshold-m from the schema
// (runtime/command_line_options.h), which override the `eval:` section, and the flag
// --options-table (the program prints EvalOptionsTable() and exits).
void AddEvalCommandLineOptions(CommandLine* command_line);
// Applies them to `options`; UsageError naming the option for a value out of the schema's range.
void ApplyEvalCommandLine(const CommandLine& command_line, EvalOptions* options);

// Writes `text` as an OutputFile (runtime/output_file.h): it appears under `path` only when
// whole, and never through a link planted beside it or at its name. Throws std::runtime_error
// naming the path.
void WriteFileAtomically(const std::string& path, const std::string& text);

// Writes each (file name, text) into `directory` (created if missing) with
// WriteFileAtomically(); returns the paths written.
std::vector<std::string> WriteTextFiles(
    const std::string& directory, const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace slammtt
