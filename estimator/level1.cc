#include "estimator/level1.h"

#include <utility>

namespace slammtt {

std::vector<Candidate> AssociateLevel1(const std::vector<Candidate>& compatible,
                                       const ScanAssociation& scan,
                                       const EstimatorOptions& options,
                                       ObservationPredictions* predicted, SlamState* state,
                                       Assignment* assignment, StepCounts* counts) {
  CompatibilitySplit split =
      SplitCompatibility(compatible, assignment->num_measurements(), assignment->num_objects());
  counts->level1_updates = ApplyPairs(split.unambiguous, options.gate_d1_chi2, scan, options,
                                      predicted, state, assignment, counts);
  return std::move(split.ambiguous);
}

}  // namespace slammtt
