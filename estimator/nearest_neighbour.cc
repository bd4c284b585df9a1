#include "estimator/nearest_neighbour.h"

namespace slammtt {

void AssociateNearestNeighbours(const std::vector<Candidate>& compatible,
                                const ScanAssociation& scan, const EstimatorOptions& options,
                                ObservationPredictions* predicted, SlamState* state,
                                Assignment* assignment, StepCounts* counts) {
  std::vector<Candidate> nearest;  // per measurement, its smallest-NIS pair
  for (const Candidate& c : compatible) {
    if (nearest.empty() || nearest.back().measurement != c.measurement) {
      nearest.push_back(c);
    } else if (c.nis < nearest.back().nis) {
      nearest.back() = c;
    }
  }
  counts->level1_updates =
      ApplyPairs(GreedyOneToOne(nearest, *assignment, PairOrder::kByNis), options.gate_d1_chi2,
                 scan, options, predicted, state, assignment, counts);
}

}  // namespace slammtt
