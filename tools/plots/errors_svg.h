// errors.svg: the robot's position error over time, estimate and odometry, and OSPA / GOSPA per
// scored scan (paper Fig. 9). A scan where neither the truth set nor the scored tracks hold an
// object (OSPA and GOSPA are 0 by definition there, docs/evaluation.md) is a gap in both lines,
// not a zero: nothing was there to be tracked. Each panel has its legend below it.
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string ErrorsSvg(const EvaluationReport& report);

// True when a scan has nothing to score: no true object in the truth set and no scored track
// (don't-cares left out).
bool NothingToTrack(const TrackingScan& scan);

}  // namespace slammtt
