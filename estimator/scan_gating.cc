#include "estimator/scan_gating.h"

#include <algorithm>
#include <limits>

namespace slammtt {

void BlockBirthsInsideHeldBackGates(const std::vector<PointMeasurement>& measurements,
                                    const std::vector<ObjectPrediction>& predictions,
                                    double new_object_gate_chi2, std::vector<double>* nearest_nis) {
  for (const ObjectPrediction& held : predictions) {
    if (!held.held_back) continue;
    ObjectPrediction judged = held;
    judged.valid = true;
    for (size_t i = 0; i < measurements.size(); ++i) {
      const double nis = NormalizedInnovationSquared(measurements[i], judged, new_object_gate_chi2);
      if (nis < new_object_gate_chi2) (*nearest_nis)[i] = std::min((*nearest_nis)[i], nis);
    }
  }
}

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
  BlockBirthsInsideHeldBackGates(measurements, predictions, options.new_object_gate_dn_chi2,
                                 &gating.nearest_nis);
  return gating;
}

}  // namespace slammtt
