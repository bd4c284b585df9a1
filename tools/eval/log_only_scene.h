// The pictures of a log without GROUND_TRUTH (a robot run, an imported recording): what the log
// holds, drawn from the log alone in the estimator's map frame (pure, EvalInput in). Nothing is
// scored; evaluation.h calls this when the log has no ground truth.
//
// - Robot: every POSE as it is; every ODOMETRY pose anchored to the estimate by the rigid
//   transform that makes them coincide at the first POSE inside the odometry's time span
//   (odometry interpolated at that utime, InterpolatePose), as evaluation.h anchors to the truth;
//   without such a POSE the odometry stays in its own frame.
// - Map: the last MAP's landmarks with their covariances, kind kUnjudged.
// - Tracks: every confirmed track labelled MOVING of every TRACKS message, per id in time order.
// - Time span: the first and last utime of POSE, ODOMETRY, TRACKS and the last MAP.
#pragma once

#include "tools/eval/eval_input.h"
#include "tools/eval/evaluation.h"

namespace slammtt {

// Fills report->log_only, landmarks, track_paths, first_utime and last_utime from `input`.
void FillLogOnlyScene(const EvalInput& input, EvaluationReport* report);

}  // namespace slammtt
