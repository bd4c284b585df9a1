// scan.svg: one scan as perception saw it (the one with the most person features): its valid
// beams, line features, point features (leg-like or not), person features and their legs, over
// the true walls, people and legs of that moment, from the robot's true pose plus the mount (in
// the sensor frame without ground truth at that utime). The legend sits below the scan.
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string ScanSvg(const EvaluationReport& report);

}  // namespace slammtt
