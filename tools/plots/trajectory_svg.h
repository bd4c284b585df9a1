// trajectory.svg: the robot's path, truth, odometry (dead reckoning) and estimate with their ATE
// (paper Fig. 12), and the smoother's (SMOOTHED_POSE) when the log has it, in the truth frame. A log without ground truth: the estimate (POSE) and the
// odometry anchored to it at its first pose, in the estimator's map frame (log_only_scene.h).
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string TrajectorySvg(const EvaluationReport& report);

}  // namespace slammtt
