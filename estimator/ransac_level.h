// Level 2 of ML-RANSAC (paper Algorithm 2, line 7): RANSAC over the associations that level 1
// left open (ml_ransac.h: RunOnePointRansac), and the plain-RANSAC baseline (b).
//
// The sample space (hypotheses are drawn from it and judged on it):
//  - ML-RANSAC: the ambiguous pairs of J whose measurement and object are both still free,
//    re-gated by d1 at the state level 1 left (their NIS recomputed there);
//  - baseline (b), kRansacAllPairs: every measurement-object pair with a finite NIS (no
//    compatibility matrix, no level 1).
// The best hypothesis' pairs are then applied gated by d1 (line 7.e: ApplyPairs, association.h),
// which the estimator does after timing RANSAC.
#pragma once

#include <random>
#include <vector>

#include "estimator/association.h"
#include "estimator/ml_ransac.h"

namespace slammtt {

// The sample space above; `ambiguous` is level 1's rest (unused for kRansacAllPairs).
std::vector<Candidate> RansacSampleSpace(const std::vector<Candidate>& ambiguous,
                                         const ScanAssociation& scan,
                                         const EstimatorOptions& options,
                                         ObservationPredictions* predicted,
                                         const SlamState& state, const Assignment& assignment);

// RANSAC over the sample space at the current state (an empty space draws nothing).
RansacOutcome RunRansacLevel(const std::vector<Candidate>& ambiguous, const ScanAssociation& scan,
                             const EstimatorOptions& options, ObservationPredictions* predicted,
                             const SlamState& state, const Assignment& assignment,
                             std::mt19937_64* rng);

}  // namespace slammtt
