#include "estimator/association.h"

#include <algorithm>
#include <limits>

#include "estimator/ekf_update.h"

namespace slammtt {

Assignment::Assignment(int num_measurements, int num_objects)
    : object_of_measurement_(static_cast<size_t>(num_measurements), -1),
      measurement_of_object_(static_cast<size_t>(num_objects), -1) {}

void Assignment::Set(int i, int j) {
  object_of_measurement_[static_cast<size_t>(i)] = j;
  measurement_of_object_[static_cast<size_t>(j)] = i;
}

int ApplyPairs(const std::vector<Candidate>& pairs, double gate_chi2, const ScanAssociation& scan,
               const EstimatorOptions& options, ObservationPredictions* predicted,
               SlamState* state, Assignment* assignment, StepCounts* counts) {
  if (pairs.empty()) return 0;
  // ApplyObservations skips gated-out pairs; gate here first so that the assignment records
  // exactly the associated pairs.
  const std::vector<ObjectPrediction>& predictions = predicted->At(*state);
  std::vector<ObjectObservation> observations;
  for (const Candidate& c : pairs) {
    if (!assignment->PairFree(c)) continue;
    const PointMeasurement& z = scan.measurements[static_cast<size_t>(c.measurement)];
    const double nis =
        NormalizedInnovationSquared(z, predictions[static_cast<size_t>(c.object)], gate_chi2);
    if (!(nis < gate_chi2)) continue;
    assignment->Set(c.measurement, c.object);
    if (!scan.may_update[static_cast<size_t>(c.object)]) {
      ++counts->static_updates_skipped;
      continue;
    }
    observations.push_back({c.object, z});
    state->object(c.object).record.last_update_utime = scan.utime;
  }
  if (observations.empty()) return 0;
  const UpdateStats stats =
      ApplyObservations(observations, options.sensor, std::numeric_limits<double>::infinity(),
                        options.update_group_size, state);
  counts->updates_failed += stats.failed;
  return stats.applied;
}

std::vector<Candidate> GreedyOneToOne(std::vector<Candidate> pairs, const Assignment& taken,
                                      PairOrder order) {
  if (order == PairOrder::kByNis) {
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const Candidate& a, const Candidate& b) { return a.nis < b.nis; });
  } else {
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  }
  Assignment local = taken;
  std::vector<Candidate> chosen;
  for (const Candidate& c : pairs) {
    if (!local.PairFree(c)) continue;
    local.Set(c.measurement, c.object);
    chosen.push_back(c);
  }
  return chosen;
}

}  // namespace slammtt
