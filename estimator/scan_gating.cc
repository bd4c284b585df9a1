#include "estimator/scan_gating.h"

#include <algorithm>
#include <limits>

namespace slammtt {

ScanGating GateScan(const std::vector<PointMeasurement>& measurements,
                    const std::vector<ObjectPrediction>& predictions,
                    const EstimatorOptions& options) {
  const double d1 = options.gate_d1_chi2;
  const double widest = std::max(
      {d1, options.new_object_gate_dn_chi2, options.level3 ? options.gate_d2_chi2 : 0.0});
  ScanGating gating;
  gating.gated = GatePairs(measurements, predictions, widest);
  gating.nearest_nis.assign(measurements.size(), std::numeric_limits<double>::infinity());
  for (const Candidate& c : gating.gated) {
    double& nearest = gating.nearest_nis[static_cast<size_t>(c.measurement)];
    nearest = std::min(nearest, c.nis);
    if (c.nis < d1) gating.compatible.push_back(c);
  }
  return gating;
}

}  // namespace slammtt
