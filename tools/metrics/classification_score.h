// Static/moving classification of the objects the estimator holds, scored per true object
// (docs/evaluation.md):
//
// - at every scan the visible true objects (static and moving) are matched to the estimator's
//   confirmed tracks (any label) by Hungarian assignment within the threshold; the label of the
//   matched track is the object's label at that scan;
// - a mover standing still (`TruthObject::standing`) is, while it stands, indistinguishable from
//   a post: the paper's method turns it into a static object (Algorithm 2, line 12, "determine
//   state of objects": moving objects become stationary and vice versa). Its scans while
//   standing take part in the matching (its track is not free for another object) but are not
//   judged: no label, right or wrong, is recorded, and they are not its first sighting. A scan
//   is "judged" for an object when it is visible and not standing;
// - final label = the label at the last judged scan in which the object was matched
//   ("untracked" if there is none); the confusion matrix counts true class x final label;
// - the scored objects are those with at least one judged visible scan; a mover seen only while
//   standing is counted apart (movers_seen_only_standing) and not scored;
// - classification accuracy = scored objects whose final label equals their true class / scored
//   objects (an object never tracked counts as wrong: it was never classified);
// - delay = time from the object's first judged visible scan (its first sighting; for a mover,
//   while moving) to the first judged matched scan from which on the label stays right in every
//   later judged matched scan (scans in which the object is not matched or not judged carry no
//   label and do not interrupt); no delay when the final label is wrong. Because an object may
//   leave the field of view for a long time, the number of judged visible scans before that
//   settling scan is reported too (visible_scans_until_right).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace slammtt {

enum class ObjectLabel { kStatic = 0, kMoving = 1, kUndecided = 2 };
// The true classes are the first two labels.
inline constexpr int kNumTrueClasses = 2;
// Final-label columns of the confusion matrix: static, moving, undecided, untracked.
inline constexpr int kNumFinalLabels = 4;
inline constexpr int kUntrackedColumn = 3;

struct TruthObject {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  ObjectLabel true_class = ObjectLabel::kStatic;  // kStatic or kMoving
  bool visible = false;
  // A kMoving object standing still at this scan (the caller's speed threshold): matched, not
  // judged (see above). Must be false for a kStatic object.
  bool standing = false;
};

struct LabelledTrack {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  ObjectLabel label = ObjectLabel::kUndecided;
};

struct ObjectClassification {
  int64_t id = 0;
  ObjectLabel true_class = ObjectLabel::kStatic;
  int64_t first_visible_utime = 0;  // first judged visible scan
  int64_t num_matched_scans = 0;    // judged scans in which it was matched
  std::optional<ObjectLabel> final_label;  // absent: never tracked
  std::optional<double> delay_s;           // absent: final label wrong or never tracked
  std::optional<int64_t> visible_scans_until_right;  // visible scans before the settling scan
  bool correct = false;
};

struct ClassificationSummary {
  std::vector<ObjectClassification> objects;  // scored objects, ordered by id
  // Movers visible only while standing still, never while moving: not scored.
  std::vector<int64_t> movers_seen_only_standing;
  // confusion[true class][final label column]
  std::array<std::array<int64_t, kNumFinalLabels>, kNumTrueClasses> confusion{};
  std::optional<double> accuracy;             // absent without any scored object
  std::optional<double> accuracy_of_tracked;  // over the objects tracked at least once
  std::optional<double> mean_delay_s;         // over the objects with a delay
  std::optional<double> max_delay_s;
  std::optional<double> mean_visible_scans_until_right;
};

class ClassificationAccumulator {
 public:
  explicit ClassificationAccumulator(double match_threshold_m);

  // One scan: every true object that exists (visible or not) and the confirmed tracks.
  // std::invalid_argument on non-finite positions, duplicate ids, a true class that is not
  // kStatic/kMoving, or a kStatic object marked standing.
  void AddScan(int64_t utime, const std::vector<TruthObject>& truth,
               const std::vector<LabelledTrack>& tracks);

  ClassificationSummary Summary() const;

 private:
  struct History {
    ObjectLabel true_class = ObjectLabel::kStatic;
    int64_t first_visible_utime = 0;
    std::vector<int64_t> visible_utimes;
    std::vector<std::pair<int64_t, ObjectLabel>> labels;  // (utime, label), judged matched
  };
  double threshold_m_;
  std::map<int64_t, History> histories_;  // objects with a judged visible scan
  std::set<int64_t> seen_standing_;       // movers visible while standing
};

}  // namespace slammtt
