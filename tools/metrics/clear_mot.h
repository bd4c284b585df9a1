// CLEAR-MOT multiple-object tracking scores (Bernardin & Stiefelhagen, "Evaluating Multiple
// Object Tracking Performance: The CLEAR MOT Metrics", EURASIP J. Image and Video Processing,
// 2008, section 2.1), frame by frame:
//
// 1. Correspondences are carried over: a true object keeps the hypothesis (track) it was last
//    matched to if both are present in this frame, their distance is within the threshold, and
//    the hypothesis has not been matched to another object since (section 2.1.1, step 1).
//    "Last matched" is the last frame in which the object was matched, not only the previous
//    frame: our truth set holds only the movers visible at a scan, so an object that drops out
//    of view for a scan would otherwise lose its correspondence (the same choice as
//    py-motmetrics; see docs/evaluation.md).
// 2. The remaining objects and hypotheses are matched optimally (Hungarian, minimum total
//    distance among the assignments with the most pairs within the threshold).
// 3. A new match whose object was last matched to a different hypothesis is an identity switch
//    (mismatch, section 2.1.1 step 3).
// 4. An unmatched hypothesis within the threshold of a "don't care" position (an existing but
//    currently invisible true object) is neither a false positive nor a match.
//
// Totals: MOTA = 1 - (misses + false positives + identity switches) / truth count (eq. 3),
// MOTP = sum of matched distances / number of matches in metres (eq. 1). A fragmentation is
// counted each time a true object, while it is in the truth set, goes from tracked to untracked
// and later back to tracked (Li, Huang & Nevatia 2009, "FM"). Match threshold: distance <= T.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace slammtt {

// An object with an identity at one moment: a true object or a tracker hypothesis.
struct IdentifiedPoint {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
};

struct ClearMotFrame {
  int num_truth = 0;
  int num_hypotheses = 0;
  int num_matches = 0;
  int num_misses = 0;
  int num_false_positives = 0;
  int num_id_switches = 0;
  int num_fragmentations = 0;  // fragmentations that ended in this frame
  int num_dont_care = 0;       // unmatched hypotheses excused by a don't-care position
  double distance_sum_m = 0.0;
  std::vector<std::pair<int64_t, int64_t>> matches;  // (truth id, hypothesis id)
  std::vector<int64_t> dont_care_hypotheses;          // their ids
};

struct ClearMotSummary {
  int64_t num_frames = 0;
  int64_t num_truth = 0;
  int64_t num_matches = 0;
  int64_t num_misses = 0;
  int64_t num_false_positives = 0;
  int64_t num_id_switches = 0;
  int64_t num_fragmentations = 0;
  int64_t num_dont_care = 0;
  double distance_sum_m = 0.0;
  std::optional<double> mota;    // absent when there was no true object at all
  std::optional<double> motp_m;  // absent when nothing was matched
};

class ClearMotAccumulator {
 public:
  // `match_threshold_m` > 0 (std::invalid_argument otherwise).
  explicit ClearMotAccumulator(double match_threshold_m);

  // Scores one frame. Ids must be unique within `truth` and within `hypotheses`, and every
  // position finite (std::invalid_argument otherwise: the caller validates log input first).
  ClearMotFrame AddFrame(const std::vector<IdentifiedPoint>& truth,
                         const std::vector<IdentifiedPoint>& hypotheses,
                         const std::vector<Eigen::Vector2d>& dont_care_positions = {});

  ClearMotSummary Summary() const;

 private:
  struct ObjectHistory {
    std::optional<int64_t> last_hypothesis;
    bool ever_tracked = false;
    bool interrupted = false;  // untracked while present since it was last tracked
  };

  double threshold_m_;
  std::map<int64_t, ObjectHistory> objects_;
  std::map<int64_t, int64_t> last_object_of_hypothesis_;
  ClearMotSummary totals_;
};

}  // namespace slammtt
