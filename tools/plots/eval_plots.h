// The evaluation's pictures, as SVG files (svg_plot.h), from an EvaluationReport (everything in
// the truth frame, estimates already anchored):
//   trajectory.svg  robot path: truth, odometry (dead reckoning) and estimate (paper Fig. 12)
//   map.svg         final static map with 2-sigma covariance ellipses over the true static
//                   objects, movers mapped as static in red (the failure of paper Fig. 5)
//   tracks.svg      confirmed moving tracks coloured per identity over the true paths of the
//                   movers (paper Figs. 6-8)
//   errors.svg      position error of estimate and odometry over time, and OSPA/GOSPA per scan
//                   (paper Fig. 9)
//   scan.svg        one scan as perception saw it (the one with the most person features): its
//                   beams, line features, point features (leg-like or not), person features
//                   and their legs, over the true walls, people and legs of that moment
// A part the log lacks is drawn as an empty panel saying so.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tools/eval/evaluation.h"

namespace slammtt {

// The five pictures as (file name, SVG document), in the order of the list above (slammtt-eval
// writes them with WriteTextFiles(), eval_log.h).
std::vector<std::pair<std::string, std::string>> EvaluationPlots(const EvaluationReport& report);

// The documents one by one.
std::string TrajectorySvg(const EvaluationReport& report);
std::string MapSvg(const EvaluationReport& report);
std::string TracksSvg(const EvaluationReport& report);
std::string ErrorsSvg(const EvaluationReport& report);
std::string ScanSvg(const EvaluationReport& report);

}  // namespace slammtt
