// Association of baseline (a), plain EKF-SLAM assuming a static world (the paper's Fig. 5;
// EstimatorOptions::mode kStaticNearestNeighbour): each measurement goes to its nearest object
// (smallest NIS) inside gate d1, one-to-one (where two measurements want one object, the closer
// one wins), and the pairs update the state together. No RANSAC, no level 3.
#pragma once

#include <vector>

#include "estimator/association.h"

namespace slammtt {

// Applies the pairs (counts->level1_updates). `compatible`: J, listed by measurement.
void AssociateNearestNeighbours(const std::vector<Candidate>& compatible,
                                const ScanAssociation& scan, const EstimatorOptions& options,
                                ObservationPredictions* predicted, SlamState* state,
                                Assignment* assignment, StepCounts* counts);

}  // namespace slammtt
