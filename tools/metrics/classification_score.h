// Static/moving classification of the objects the estimator holds, scored per true object
// (docs/evaluation.md):
//
// - at every scan the visible true objects (static and moving) are matched to the estimator's
//   confirmed tracks (any label) by Hungarian assignment within the threshold; the label of the
//   matched track is the object's label at that scan;
// - final label = the label at the last scan in which the object was matched ("untracked" if it
//   never was); the confusion matrix counts true class x final label;
// - classification accuracy = objects whose final label equals their true class / objects ever
//   visible (an object never tracked counts as wrong: it was never classified);
// - delay = time from the object's first visible scan to the first matched scan from which on the
//   label stays right in every later matched scan (scans in which the object is not matched
//   carry no label and do not interrupt); no delay when the final label is wrong. Because an
//   object may leave the field of view for a long time, the number of scans in which it was
//   visible before that settling scan is reported too (visible_scans_until_right).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
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
};

struct LabelledTrack {
  int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  ObjectLabel label = ObjectLabel::kUndecided;
};

struct ObjectClassification {
  int64_t id = 0;
  ObjectLabel true_class = ObjectLabel::kStatic;
  int64_t first_visible_utime = 0;
  int64_t num_matched_scans = 0;
  std::optional<ObjectLabel> final_label;  // absent: never tracked
  std::optional<double> delay_s;           // absent: final label wrong or never tracked
  std::optional<int64_t> visible_scans_until_right;  // visible scans before the settling scan
  bool correct = false;
};

struct ClassificationSummary {
  std::vector<ObjectClassification> objects;  // ordered by id
  // confusion[true class][final label column]
  std::array<std::array<int64_t, kNumFinalLabels>, kNumTrueClasses> confusion{};
  std::optional<double> accuracy;             // absent without any visible object
  std::optional<double> accuracy_of_tracked;  // over the objects tracked at least once
  std::optional<double> mean_delay_s;         // over the objects with a delay
  std::optional<double> max_delay_s;
  std::optional<double> mean_visible_scans_until_right;
};

class ClassificationAccumulator {
 public:
  explicit ClassificationAccumulator(double match_threshold_m);

  // One scan: every true object that exists (visible or not) and the confirmed tracks.
  // std::invalid_argument on non-finite positions, duplicate ids, or a true class that is
  // not kStatic/kMoving.
  void AddScan(int64_t utime, const std::vector<TruthObject>& truth,
               const std::vector<LabelledTrack>& tracks);

  ClassificationSummary Summary() const;

 private:
  struct History {
    ObjectLabel true_class = ObjectLabel::kStatic;
    int64_t first_visible_utime = 0;
    std::vector<int64_t> visible_utimes;
    std::vector<std::pair<int64_t, ObjectLabel>> labels;  // (utime, label) of matched scans
  };
  double threshold_m_;
  std::map<int64_t, History> histories_;  // objects ever visible
};

}  // namespace slammtt
