// tracks.svg: the confirmed moving tracks, one colour per identity with the id written at each
// track's last position (so that an identity switch can be read off the picture), over the true
// paths of the movers (paper Figs. 6-8). Without ground truth: every confirmed moving track of
// the log with the estimated robot path, in the estimator's map frame.
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string TracksSvg(const EvaluationReport& report);

}  // namespace slammtt
