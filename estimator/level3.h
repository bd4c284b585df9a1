// Level 3 of ML-RANSAC (paper Algorithm 2, line 9; EstimatorOptions::level3): what levels 1 and
// 2 left unassigned is tried again with the wider gate d2 > d1, at the state they (and the
// manoeuvres, manoeuvres.h) left.
//
// The free pairs under d2 compete greedily, one-to-one, in increasing cost NIS + ln det S
// (PairCost, gating.h), not by the NIS alone: a wide object (a track coasting unseen, a
// one-scan-old object) has a small NIS to any measurement nearby and would otherwise take the
// measurement of a well-known landmark. The chosen pairs are applied gated by d2.
#pragma once

#include <vector>

#include "estimator/association.h"

namespace slammtt {

// The free pairs under d2 at the current state, each with its cost, listed by measurement then
// object.
std::vector<Candidate> Level3Candidates(const ScanAssociation& scan,
                                        const EstimatorOptions& options,
                                        ObservationPredictions* predicted,
                                        const SlamState& state, const Assignment& assignment);

// Chooses and applies the pairs (counts->level3_updates).
void AssociateLevel3(const ScanAssociation& scan, const EstimatorOptions& options,
                     ObservationPredictions* predicted, SlamState* state, Assignment* assignment,
                     StepCounts* counts);

}  // namespace slammtt
