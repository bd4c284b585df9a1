// Identity-aware tracking scores that users compare with published figures, beside CLEAR-MOT
// (clear_mot.h): IDF1 and HOTA, on points in the plane with a distance threshold.
//
// IDF1 (Ristani, Solera, Zou, Cucchiara, Tomasi, "Performance Measures and a Data Set for
// Multi-Target, Multi-Camera Tracking", ECCV workshops 2016, section 4): every true trajectory is
// matched to at most one hypothesis trajectory, for the whole run, by the bipartite matching that
// maximises the number of frames in which the two are both present and within the threshold
// (IDTP). IDFN = true detections - IDTP, IDFP = hypothesis detections - IDTP,
//   IDF1 = 2 IDTP / (2 IDTP + IDFP + IDFN),  IDP = IDTP / (IDTP + IDFP),  IDR = IDTP / (IDTP + IDFN).
//
// HOTA (Luiten, Osep, Dendorfer, Torr, Geiger, Leal-Taixe, Leibe, "HOTA: A Higher Order Metric
// for Evaluating Multi-Object Tracking", IJCV 129, 2021, sections 5-6; TrackEval's definitions),
// with the similarity of a true object and a hypothesis at distance d taken as
//   S = max(0, 1 - d / threshold)
// (the localisation similarity of the HOTA paper's point-tracking variant; IoU for boxes):
//  1. Over the whole run, per pair (true id i, hypothesis id j), the alignment score
//     A(i, j) = sum_t S'_t(i, j) / (n_i + n_j - sum_t S'_t(i, j)), with n the frames each is
//     present and S' the similarity normalised as TrackEval does (S / (row sum + column sum - S)).
//  2. Per frame, one Hungarian matching that maximises A(i, j) * S_t(i, j) (a pair with S = 0 is
//     never matched).
//  3. For each alpha in {0.05, 0.10, ..., 0.95}: matched pairs with S >= alpha are true
//     positives; DetA = TP / (TP + FN + FP); per TP pair, its association score
//     |TPA| / (|TPA| + |FNA| + |FPA|) over the run; AssA = their mean; LocA = mean S of the TPs;
//     HOTA_alpha = sqrt(DetA * AssA). HOTA, DetA, AssA, LocA are the means over the 19 alphas.
//
// Both are computed on exactly the frames the caller gives, after the caller's don't-care rules
// (evaluation.h removes excused hypotheses and invisible or standing movers first, as TrackEval's
// preprocessing removes distractors).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "tools/metrics/clear_mot.h"

namespace slammtt {

struct IdentityScores {
  int64_t num_frames = 0;
  int64_t num_truth_detections = 0;
  int64_t num_hypothesis_detections = 0;
  int64_t id_true_positives = 0;   // IDTP
  int64_t id_false_negatives = 0;  // IDFN
  int64_t id_false_positives = 0;  // IDFP
  std::optional<double> idf1;      // absent when there is neither truth nor hypothesis
  std::optional<double> id_precision;
  std::optional<double> id_recall;
  std::optional<double> hota;
  std::optional<double> det_a;
  std::optional<double> ass_a;
  std::optional<double> loc_a;
};

// Collects frames, scores at the end (both metrics need the whole run).
class IdentityMetricsAccumulator {
 public:
  // `match_threshold_m` > 0 (std::invalid_argument otherwise).
  explicit IdentityMetricsAccumulator(double match_threshold_m);

  // One frame. Ids unique within each list, positions finite (std::invalid_argument otherwise).
  void AddFrame(const std::vector<IdentifiedPoint>& truth,
                const std::vector<IdentifiedPoint>& hypotheses);

  IdentityScores Scores() const;

 private:
  struct Frame {
    std::vector<IdentifiedPoint> truth;
    std::vector<IdentifiedPoint> hypotheses;
  };
  double threshold_m_;
  std::vector<Frame> frames_;
};

}  // namespace slammtt
