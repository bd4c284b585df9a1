#include "estimator/scan_gating.h"

#include <algorithm>
#include <cmath>
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
  gating.held_back_nis.assign(measurements.size(), std::numeric_limits<double>::infinity());
  BlockBirthsInsideHeldBackGates(measurements, predictions, options.new_object_gate_dn_chi2,
                                 &gating.held_back_nis);
  for (size_t i = 0; i < measurements.size(); ++i) {
    gating.nearest_nis[i] = std::min(gating.nearest_nis[i], gating.held_back_nis[i]);
  }
  return gating;
}

namespace {

// The distance between two measured points of one scan (both in the sensor's frame).
double SeparationM(const PointMeasurement& a, const PointMeasurement& b) {
  const auto point = [](const PointMeasurement& z) {
    return Eigen::Vector2d(z.range_bearing(0) * std::cos(z.range_bearing(1)),
                           z.range_bearing(0) * std::sin(z.range_bearing(1)));
  };
  return (point(a) - point(b)).norm();
}

}  // namespace

std::vector<double> NearestNisForBirths(const std::vector<PointMeasurement>& measurements,
                                        const ScanGating& gating, const Assignment& assignment,
                                        const SlamState& state, const EstimatorOptions& options) {
  if (!options.new_object_gate_skips_claimed_objects) return gating.nearest_nis;
  std::vector<double> nearest = gating.held_back_nis;
  for (const Candidate& c : gating.gated) {
    const int own = assignment.MeasurementOf(c.object);
    const ObjectRecord& record = state.object(c.object).record;
    const bool still_blocks = record.kind == ObjectKind::kPerson ||
                              record.object_class == ObjectClass::kMoving ||
                              (own >= 0 && measurements[static_cast<size_t>(own)].person);
    if (own >= 0 && !still_blocks &&
        SeparationM(measurements[static_cast<size_t>(own)],
                    measurements[static_cast<size_t>(c.measurement)]) >=
            options.new_object_beside_claimed_min_separation_m) {
      continue;
    }
    double& n = nearest[static_cast<size_t>(c.measurement)];
    n = std::min(n, c.nis);
  }
  return nearest;
}

std::vector<int> ClaimedObjectsBesideBirths(const ScanGating& gating,
                                            const std::vector<double>& birth_nis,
                                            const Assignment& assignment, double dn_chi2) {
  std::vector<int> beside;
  for (const Candidate& c : gating.gated) {
    const auto i = static_cast<size_t>(c.measurement);
    if (!assignment.MeasurementFree(c.measurement) || assignment.ObjectFree(c.object) ||
        c.nis >= dn_chi2 || birth_nis[i] < dn_chi2 || gating.nearest_nis[i] >= dn_chi2) {
      continue;
    }
    beside.push_back(c.object);
  }
  std::sort(beside.begin(), beside.end());
  beside.erase(std::unique(beside.begin(), beside.end()), beside.end());
  return beside;
}

}  // namespace slammtt
