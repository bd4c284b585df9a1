// The evaluation's pictures, as SVG files (svg_plot.h), from an EvaluationReport: everything in
// the truth frame with the estimates anchored, or, for a log without ground truth, what the log
// holds in the estimator's map frame (log_only_scene.h). One file pair per picture:
//   trajectory.svg  trajectory_svg.h  robot path: truth, odometry and estimate (paper Fig. 12)
//   map.svg         map_svg.h         final static map, 2-sigma ellipses and landmark ids, over
//                                     the true static objects (paper Fig. 5)
//   tracks.svg      tracks_svg.h      confirmed moving tracks per identity over the true paths
//                                     (paper Figs. 6-8)
//   identities.svg  timeline_svg.h    per true mover, the track matched to it over time, with
//                                     identity switches and fragmentations
//   errors.svg      errors_svg.h      position error over time, OSPA/GOSPA per scan (Fig. 9)
//   scan.svg        scan_svg.h        one scan as perception saw it
// Every legend sits outside the data area; a part the log lacks is an empty panel saying so.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tools/eval/evaluation.h"
#include "tools/plots/errors_svg.h"
#include "tools/plots/map_svg.h"
#include "tools/plots/scan_svg.h"
#include "tools/plots/timeline_svg.h"
#include "tools/plots/tracks_svg.h"
#include "tools/plots/trajectory_svg.h"

namespace slammtt {

// The pictures as (file name, SVG document), in the order of the list above (slammtt-eval
// writes them with WriteTextFiles(), eval_log.h).
std::vector<std::pair<std::string, std::string>> EvaluationPlots(const EvaluationReport& report);

}  // namespace slammtt
