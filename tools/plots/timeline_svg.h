// identities.svg: the identities over time. One row per true mover that is ever in the tracking
// truth set (docs/evaluation.md: visible and in motion), time along x; at each scored scan where
// the mover is in the truth set, a bar in the colour of the track CLEAR-MOT matched to it (its
// id written where a run of one track starts and there is room), grey when it is untracked (a
// miss), nothing where it is not in the truth set (invisible or standing). A triangle above the
// bar marks each identity switch, a diamond below it each fragmentation (tracked again after a
// gap), at the scan where slammtt-eval counts it: as many markers as the report's id_switches
// and fragmentations. Without tracking scores (no ground truth, no TRACKS) a panel that says so.
#pragma once

#include <string>

#include "tools/eval/evaluation.h"

namespace slammtt {

std::string IdentityTimelineSvg(const EvaluationReport& report);

}  // namespace slammtt
