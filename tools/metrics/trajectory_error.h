// Absolute trajectory error (ATE) of a planar robot trajectory against ground truth, after the
// estimate has been anchored to the truth by a rigid transform at the first common time (no
// least-squares alignment: an estimator must not get credit for a fit it did not make). This is
// the "absolute trajectory error" of Sturm et al., "A Benchmark for the Evaluation of RGB-D SLAM
// Systems", IROS 2012, section VI.B, restricted to SE(2) and with the alignment replaced by the
// first-pose anchoring. Definitions in docs/evaluation.md.
#pragma once

#include <cstdint>
#include <vector>

#include "tools/metrics/pose2.h"

namespace slammtt {

// A true and an estimated pose at the same moment, both in the truth's frame.
struct PosePair {
  int64_t utime = 0;
  Pose2 truth;
  Pose2 estimate;
};

struct TrajectoryError {
  // Per pair, in input order.
  std::vector<int64_t> utime;
  std::vector<double> position_error_m;    // |p_truth - p_estimate|
  std::vector<double> heading_error_rad;   // wrap(estimate - truth)
  // Summary; every value is 0 for an empty input (count says so).
  int64_t count = 0;
  double rmse_m = 0.0;
  double mean_m = 0.0;
  double max_m = 0.0;
  int64_t max_utime = 0;
  double final_position_error_m = 0.0;
  double final_heading_error_rad = 0.0;    // signed, at the last pair
  double heading_rmse_rad = 0.0;
};

// Scores pairs that are already in one frame. std::invalid_argument on a non-finite pose.
TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs);

// Re-expresses every estimate through the anchor computed from the first pair, so that the first
// pair coincides exactly. Returns the anchor (identity for an empty input).
Pose2 AnchorAtFirstPair(std::vector<PosePair>* pairs);

// The rigid transform T that minimises sum |p_truth - T p_estimate|^2 over the pairs' positions
// (Umeyama, "Least-squares estimation of transformation parameters between two point
// patterns", IEEE TPAMI 13(4), 1991, without scale, in the plane): what evo's `--align` does,
// for comparison with published figures. Identity for fewer than 2 pairs; with all estimates at
// one point, only the translation is fitted.
Pose2 LeastSquaresAlignment(const std::vector<PosePair>& pairs);

// Relative pose error over consecutive pairs (Sturm et al., IROS 2012, section VI.A, with a
// step of one pair; evo_rpe's default delta of 1): for each i,
// E_i = (Q_i^-1 Q_i+1)^-1 (P_i^-1 P_i+1), Q the truth and P the estimate; the translation norm
// and the wrapped angle of E_i. Independent of any anchoring or alignment.
struct RelativePoseError {
  int64_t count = 0;
  double translation_rmse_m = 0.0;
  double translation_mean_m = 0.0;
  double translation_max_m = 0.0;
  double rotation_rmse_rad = 0.0;
};
RelativePoseError EvaluateRelativePoseError(const std::vector<PosePair>& pairs);

}  // namespace slammtt
