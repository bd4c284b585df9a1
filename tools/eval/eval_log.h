// Reads the channels slammtt-eval needs from an LCM log into EvalInput: GROUND_TRUTH, ODOMETRY,
// POSE, TRACKS and MAP (channel names from the stack's Channels). A message that cannot be
// decoded, holds a non-finite number or one beyond 1e6 (metres, m/s, covariance entries), a
// utime outside [0, 1e18] us, an unknown class, duplicate object ids, or repeats the utime of an
// earlier one of its channel is rejected and counted (EvalInput::rejected), never used;
// messages are sorted by utime per channel (a live recording may interleave them).
#pragma once

#include <string>

#include "runtime/channels.h"
#include "tools/eval/eval_input.h"
#include "tools/replay/log_events.h"

namespace slammtt {

// Throws std::runtime_error when the log cannot be opened. `read` receives the damage report.
EvalInput ReadEvalInput(const std::string& path, const Channels& channels, LogReadResult* read);

}  // namespace slammtt
