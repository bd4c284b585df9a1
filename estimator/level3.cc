#include "estimator/level3.h"

namespace slammtt {

std::vector<Candidate> Level3Candidates(const ScanAssociation& scan,
                                        const EstimatorOptions& options,
                                        ObservationPredictions* predicted,
                                        const SlamState& state, const Assignment& assignment) {
  const double d2 = options.gate_d2_chi2;
  const std::vector<PointMeasurement>& measurements = scan.measurements;
  const std::vector<ObjectPrediction>& predictions = predicted->At(state);
  std::vector<int> free_measurements;
  std::vector<int> free_objects;
  for (int i = 0; i < assignment.num_measurements(); ++i) {
    if (assignment.MeasurementFree(i)) free_measurements.push_back(i);
  }
  for (int j = 0; j < assignment.num_objects(); ++j) {
    if (assignment.ObjectFree(j)) free_objects.push_back(j);
  }
  std::vector<Candidate> remaining;
  if (free_measurements.size() * free_objects.size() <= kGatingBruteForcePairs) {
    for (int i : free_measurements) {
      for (int j : free_objects) {
        const double nis = NormalizedInnovationSquared(measurements[static_cast<size_t>(i)],
                                                       predictions[static_cast<size_t>(j)], d2);
        if (nis < d2) remaining.push_back({i, j, nis});
      }
    }
  } else {
    // Same pairs, same order, looked up by bearing (gating.h).
    for (const Candidate& c : GatePairs(measurements, predictions, d2)) {
      if (assignment.PairFree(c)) remaining.push_back(c);
    }
  }
  for (Candidate& c : remaining) {
    c.cost = PairCost(measurements[static_cast<size_t>(c.measurement)],
                      predictions[static_cast<size_t>(c.object)], c.nis);
  }
  return remaining;
}

void AssociateLevel3(const ScanAssociation& scan, const EstimatorOptions& options,
                     ObservationPredictions* predicted, SlamState* state, Assignment* assignment,
                     StepCounts* counts) {
  const std::vector<Candidate> chosen = GreedyOneToOne(
      Level3Candidates(scan, options, predicted, *state, *assignment), *assignment,
      PairOrder::kByCost);
  counts->level3_updates = ApplyPairs(chosen, options.gate_d2_chi2, scan, options, predicted,
                                      state, assignment, counts);
}

}  // namespace slammtt
