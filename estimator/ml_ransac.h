// Level 2 of ML-RANSAC (paper Algorithm 2, line 7): RANSAC over the associations that the
// compatibility matrix J leaves ambiguous, read as 1-point RANSAC for the EKF (Civera et al.
// 2010, the paper's ref. [30]).
//
// Minimal sample: one allowed pair (measurement i, object j), m = 1 in eq. 16. A hypothesis
// (line 7.c.i-v):
//   - updates the state MEAN with that pair alone (x_h = x + P H^T S^-1 nu; only the rows of
//     the robot and of the objects being judged are computed: O(objects) per hypothesis);
//   - predicts every other measurement of the evaluation set from x_h, with the innovation
//     covariance conditioned on the hypothesis (S_h = H P_h H^T + R, where P_h = P - W S^-1 W^T
//     restricted to the 5 states the pair touches: exact for the linearised model);
//   - takes, one-to-one (each measurement and each object at most once, the hypothesis' own
//     pair first), the pairs with NIS under `inlier_chi2` in increasing cost, NIS + ln det S
//     (PairCost, gating.h): that set is the consensus.
// The best hypothesis has the largest consensus; ties go to the smaller total cost (the
// inliers' negative log-likelihood, as MLESAC scores, Torr and Zisserman 2000: with the NIS
// alone, the hypothesis that gives a measurement to a poorly known object beats the one that
// gives it to the landmark it belongs to), then to the earlier pair in the input, so the
// winner does not depend on the drawing order when every pair gets drawn.
// Hypotheses are drawn without replacement (a pair drawn twice gives the same hypothesis), so
// at most |sample space| are generated. Their number adapts by eq. 16 with m = 1:
// n_hyp = log(1 - p) / log(eps), eps = 1 - N_in / N_IC, where N_in is the best consensus and
// N_IC the number of individually compatible pairs in the sample space (line 7.c.vi.2-3), and
// never exceeds the cap N (line 7.b). The work of a scan is bounded too: a hypothesis tests
// every pair of the evaluation set, and no hypothesis starts once the tests so far and its own
// would exceed max_pair_tests (the first always runs); the outcome says so (budget_cut).
// Without it, the cap N alone let one hostile scan take 121 s (1 000 hypotheses over millions
// of pairs).
//
// The same routine is the plain-RANSAC baseline (b) when the sample space is every pair.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "common/options_schema.h"

#include "estimator/gating.h"
#include "estimator/point_measurement.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct RansacOptions {
  double success_probability = 0.99;  // p of eq. 16 (paper: 0.99)
  int max_hypotheses = 1000;          // N (paper: "for example 1000")
  double inlier_chi2 = 5.99;          // consensus threshold on the conditioned NIS (95 %, 2 dof)
  // Pair tests per scan (hypotheses x evaluation pairs): 1e6 is about 50 ms on this machine,
  // 50 times the most any shipped scenario needs (docs/estimator.md, "Hostile sizes").
  int64_t max_pair_tests = 1000000;
};

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `ransac`).
void VisitRansacOptions(OptionVisitor* visitor, RansacOptions* options);

struct RansacOutcome {
  std::vector<Candidate> consensus;  // pairs of the best hypothesis, its own pair first
  int hypotheses = 0;                // hypotheses generated
  int best_pair = -1;                // index of the winning pair in the sample space
  int64_t pair_tests = 0;            // evaluation pairs tested, over every hypothesis
  bool budget_cut = false;           // max_pair_tests stopped it before eq. 16 or N did
};

// `sample_space`: the pairs hypotheses are drawn from. `evaluation`: the pairs whose
// consistency is counted (usually the same set). `predictions` are those of every object at
// the current state (gating.h). An empty sample space gives an empty outcome and draws nothing.
RansacOutcome RunOnePointRansac(const SlamState& state,
                                const std::vector<PointMeasurement>& measurements,
                                const std::vector<ObjectPrediction>& predictions,
                                const std::vector<Candidate>& sample_space,
                                const std::vector<Candidate>& evaluation,
                                const SensorMount& mount, const RansacOptions& options,
                                std::mt19937_64* rng);

// Eq. 16 with m = 1: hypotheses needed so that one is an inlier with probability p when a
// fraction inlier_ratio of the sample space are inliers. 0 when inlier_ratio >= 1.
double RequiredHypotheses(double inlier_ratio, double success_probability);

// Uniform integer in [0, n) from the generator alone (rejection sampling), the same on every
// standard library, unlike std::uniform_int_distribution. n >= 1.
uint64_t UniformIndex(std::mt19937_64* rng, uint64_t n);

}  // namespace slammtt
