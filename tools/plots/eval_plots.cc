#include "tools/plots/eval_plots.h"

namespace slammtt {

std::vector<std::pair<std::string, std::string>> EvaluationPlots(const EvaluationReport& report) {
  return {{"trajectory.svg", TrajectorySvg(report)},
          {"map.svg", MapSvg(report)},
          {"tracks.svg", TracksSvg(report)},
          {"identities.svg", IdentityTimelineSvg(report)},
          {"errors.svg", ErrorsSvg(report)},
          {"scan.svg", ScanSvg(report)}};
}

}  // namespace slammtt
