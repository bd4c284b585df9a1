// Level 1 of ML-RANSAC (paper Algorithm 2, lines 5-6): the pairs the compatibility matrix J
// settles, those that are the only candidate of their measurement and of their object
// (gating.h: SplitCompatibility), update the state together, gated by d1.
#pragma once

#include <vector>

#include "estimator/association.h"

namespace slammtt {

// Applies J's unambiguous pairs (counts->level1_updates) and returns the ambiguous rest, for
// RANSAC (ransac_level.h).
std::vector<Candidate> AssociateLevel1(const std::vector<Candidate>& compatible,
                                       const ScanAssociation& scan,
                                       const EstimatorOptions& options,
                                       ObservationPredictions* predicted, SlamState* state,
                                       Assignment* assignment, StepCounts* counts);

}  // namespace slammtt
