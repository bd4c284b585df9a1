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
// 4. "Don't care" (DontCare below): what is left of the hypotheses after steps 1-3 may be
//    excused, i.e. counted neither as a false positive nor as a match. First, each don't-care
//    object (an object that is seen but need not be tracked now: a mover standing still) excuses
//    the one hypothesis the optimal assignment within the threshold gives it. Then every
//    hypothesis within the threshold of a don't-care position (an object that exists but cannot
//    be seen: occluded, out of view, too few beams) is excused: a tracker coasting through an
//    occlusion is right to. Don't-care objects are not in the truth set: their correspondence
//    history (last matched hypothesis, fragmentation state) stays as it was, as for an object
//    absent from the frame.
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

// What is present at a frame but neither to be tracked nor to be held against the tracker
// (step 4 above).
struct DontCare {
  // Seen, but need not be tracked now: each excuses at most one hypothesis (optimal assignment
  // within the threshold among the hypotheses left unmatched by the truth set). Ids must not
  // repeat and must not be in the frame's truth set.
  std::vector<IdentifiedPoint> objects;
  // Exist but cannot be seen: every unmatched hypothesis within the threshold is excused.
  std::vector<Eigen::Vector2d> positions;
};

// A new correspondence of a true object that contradicts its last one (step 3).
struct IdentitySwitch {
  int64_t truth_id = 0;
  int64_t previous_hypothesis_id = 0;
  int64_t new_hypothesis_id = 0;
};

// A true object tracked again after it was untracked while in the truth set.
struct Fragmentation {
  int64_t truth_id = 0;
  int64_t previous_hypothesis_id = 0;  // the hypothesis it was last matched to
  int64_t new_hypothesis_id = 0;       // the hypothesis it is matched to now (may be the same)
  int64_t untracked_since_frame = 0;   // index (0-based, in AddFrame order) of the first frame
                                       // in which it was in the truth set and unmatched
};

struct ClearMotFrame {
  int num_truth = 0;
  int num_hypotheses = 0;
  int num_matches = 0;
  int num_misses = 0;
  int num_false_positives = 0;
  int num_id_switches = 0;
  int num_fragmentations = 0;  // fragmentations that ended in this frame
  int num_dont_care = 0;       // unmatched hypotheses excused (both kinds below)
  int num_dont_care_objects = 0;    // ... by a don't-care object (DontCare::objects)
  int num_dont_care_positions = 0;  // ... by a don't-care position (DontCare::positions)
  double distance_sum_m = 0.0;
  std::vector<std::pair<int64_t, int64_t>> matches;  // (truth id, hypothesis id)
  std::vector<int64_t> dont_care_hypotheses;          // ids of the excused hypotheses
  std::vector<IdentitySwitch> id_switches;            // one per counted switch
  std::vector<Fragmentation> fragmentations;          // one per counted fragmentation
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
  int64_t num_dont_care_objects = 0;
  int64_t num_dont_care_positions = 0;
  double distance_sum_m = 0.0;
  std::optional<double> mota;    // absent when there was no true object at all
  std::optional<double> motp_m;  // absent when nothing was matched
};

class ClearMotAccumulator {
 public:
  // `match_threshold_m` > 0 (std::invalid_argument otherwise).
  explicit ClearMotAccumulator(double match_threshold_m);

  // Scores one frame. Ids must be unique within `truth`, within `hypotheses` and within
  // `dont_care.objects`, no don't-care object may share an id with `truth`, and every position
  // must be finite (std::invalid_argument otherwise: the caller validates log input first).
  ClearMotFrame AddFrame(const std::vector<IdentifiedPoint>& truth,
                         const std::vector<IdentifiedPoint>& hypotheses,
                         const DontCare& dont_care = {});

  ClearMotSummary Summary() const;

 private:
  struct ObjectHistory {
    std::optional<int64_t> last_hypothesis;
    bool ever_tracked = false;
    bool interrupted = false;  // untracked while present since it was last tracked
    int64_t interrupted_since_frame = 0;
  };

  double threshold_m_;
  std::map<int64_t, ObjectHistory> objects_;
  std::map<int64_t, int64_t> last_object_of_hypothesis_;
  ClearMotSummary totals_;
};

}  // namespace slammtt
