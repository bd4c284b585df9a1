#include "estimator/ransac_level.h"

#include <cmath>
#include <limits>

namespace slammtt {

std::vector<Candidate> RansacSampleSpace(const std::vector<Candidate>& ambiguous,
                                         const ScanAssociation& scan,
                                         const EstimatorOptions& options,
                                         ObservationPredictions* predicted,
                                         const SlamState& state, const Assignment& assignment) {
  std::vector<Candidate> sample_space;
  const std::vector<PointMeasurement>& measurements = scan.measurements;
  if (options.mode == AssociationMode::kRansacAllPairs) {
    const std::vector<ObjectPrediction>& predictions = predicted->At(state);
    for (int i = 0; i < assignment.num_measurements(); ++i) {
      for (int j = 0; j < assignment.num_objects(); ++j) {
        const double nis = NormalizedInnovationSquared(measurements[static_cast<size_t>(i)],
                                                       predictions[static_cast<size_t>(j)],
                                                       std::numeric_limits<double>::infinity());
        if (std::isfinite(nis)) sample_space.push_back({i, j, nis});
      }
    }
    return sample_space;
  }
  if (ambiguous.empty()) return sample_space;
  const double d1 = options.gate_d1_chi2;
  const std::vector<ObjectPrediction>& predictions = predicted->At(state);
  for (const Candidate& c : ambiguous) {
    if (!assignment.PairFree(c)) continue;
    const double nis =
        NormalizedInnovationSquared(measurements[static_cast<size_t>(c.measurement)],
                                    predictions[static_cast<size_t>(c.object)], d1);
    if (nis < d1) sample_space.push_back({c.measurement, c.object, nis});
  }
  return sample_space;
}

RansacOutcome RunRansacLevel(const std::vector<Candidate>& ambiguous, const ScanAssociation& scan,
                             const EstimatorOptions& options, ObservationPredictions* predicted,
                             const SlamState& state, const Assignment& assignment,
                             std::mt19937_64* rng) {
  const std::vector<Candidate> sample_space =
      RansacSampleSpace(ambiguous, scan, options, predicted, state, assignment);
  if (sample_space.empty()) return RansacOutcome();
  return RunOnePointRansac(state, scan.measurements, predicted->At(state), sample_space,
                           sample_space, options.sensor, options.ransac, rng);
}

}  // namespace slammtt
