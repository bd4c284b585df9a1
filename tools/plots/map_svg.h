// map.svg: the final static map, each landmark with its 2-sigma covariance ellipse and its id
// (small labels placed so that they do not overlap each other where avoidable,
// label_placement.h), over the true static objects, walls and mover paths; landmarks on a
// mover's path in red (the failure of paper Fig. 5). Without ground truth: the landmarks alone
// (unjudged) with the estimated robot path, in the estimator's map frame.
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string MapSvg(const EvaluationReport& report);

}  // namespace slammtt
