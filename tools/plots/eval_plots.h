// The evaluation's pictures, as SVG files (svg_plot.h), from an EvaluationReport (everything in
// the truth frame, estimates already anchored):
//   trajectory.svg  robot path: truth, odometry (dead reckoning) and estimate (paper Fig. 12)
//   map.svg         final static map with 2-sigma covariance ellipses over the true static
//                   objects, movers mapped as static in red (the failure of paper Fig. 5)
//   tracks.svg      confirmed moving tracks coloured per identity over the true paths of the
//                   movers (paper Figs. 6-8)
//   errors.svg      position error of estimate and odometry over time, and OSPA/GOSPA per scan
//                   (paper Fig. 9)
// A part the log lacks is drawn as an empty panel saying so.
#pragma once

#include <string>
#include <vector>

#include "tools/eval/evaluation.h"

namespace slammtt {

// Writes the four pictures into `directory` (created if missing) and returns their paths.
// Throws std::runtime_error naming the file on an I/O error.
std::vector<std::string> WriteEvaluationPlots(const EvaluationReport& report,
                                              const std::string& directory);

// The documents themselves, for tests and for callers that write elsewhere.
std::string TrajectorySvg(const EvaluationReport& report);
std::string MapSvg(const EvaluationReport& report);
std::string TracksSvg(const EvaluationReport& report);
std::string ErrorsSvg(const EvaluationReport& report);

}  // namespace slammtt
