#include "tools/metrics/classification_score.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "common/utime.h"
#include "tools/metrics/assignment.h"

namespace slammtt {

ClassificationAccumulator::ClassificationAccumulator(double match_threshold_m)
    : threshold_m_(match_threshold_m) {
  if (!(match_threshold_m > 0.0) || !std::isfinite(match_threshold_m)) {
    throw std::invalid_argument("classification: match threshold must be a positive number");
  }
}

void ClassificationAccumulator::AddScan(int64_t utime, const std::vector<TruthObject>& truth,
                                        const std::vector<LabelledTrack>& tracks) {
  std::set<int64_t> ids;
  std::vector<const TruthObject*> visible;
  for (const TruthObject& object : truth) {
    if (!ids.insert(object.id).second) {
      throw std::invalid_argument("classification: duplicate truth id " +
                                  std::to_string(object.id));
    }
    if (object.true_class == ObjectLabel::kUndecided) {
      throw std::invalid_argument("classification: a true class must be static or moving");
    }
    if (!object.position_m.allFinite()) {
      throw std::invalid_argument("classification: non-finite truth position");
    }
    if (object.standing && object.true_class != ObjectLabel::kMoving) {
      throw std::invalid_argument("classification: only a mover can stand still");
    }
    if (object.visible) visible.push_back(&object);
  }
  ids.clear();
  for (const LabelledTrack& track : tracks) {
    if (!ids.insert(track.id).second) {
      throw std::invalid_argument("classification: duplicate track id " +
                                  std::to_string(track.id));
    }
    if (!track.position_m.allFinite()) {
      throw std::invalid_argument("classification: non-finite track position");
    }
  }

  for (const TruthObject* object : visible) {
    if (object->standing) {
      seen_standing_.insert(object->id);
      continue;
    }
    auto [it, inserted] = histories_.try_emplace(object->id);
    if (inserted) {
      it->second.true_class = object->true_class;
      it->second.first_visible_utime = utime;
    }
    it->second.visible_utimes.push_back(utime);
  }
  Eigen::MatrixXd cost(visible.size(), tracks.size());
  for (size_t i = 0; i < visible.size(); ++i) {
    for (size_t j = 0; j < tracks.size(); ++j) {
      const double d = (visible[i]->position_m - tracks[j].position_m).norm();
      cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          d <= threshold_m_ ? d : kForbiddenCost;
    }
  }
  const Assignment assignment = SolveMinCostAssignment(cost);
  for (size_t i = 0; i < visible.size(); ++i) {
    const int j = assignment.row_to_col[i];
    if (j < 0 || visible[i]->standing) continue;
    histories_.at(visible[i]->id)
        .labels.emplace_back(utime, tracks[static_cast<size_t>(j)].label);
  }
}

ClassificationSummary ClassificationAccumulator::Summary() const {
  ClassificationSummary summary;
  int64_t correct = 0;
  int64_t tracked = 0;
  double delay_sum_s = 0.0;
  int64_t num_delays = 0;
  int64_t visible_scans_sum = 0;
  for (const auto& [id, history] : histories_) {
    ObjectClassification object;
    object.id = id;
    object.true_class = history.true_class;
    object.first_visible_utime = history.first_visible_utime;
    object.num_matched_scans = static_cast<int64_t>(history.labels.size());
    const int row = static_cast<int>(history.true_class);
    if (history.labels.empty()) {
      ++summary.confusion[row][kUntrackedColumn];
      summary.objects.push_back(object);
      continue;
    }
    ++tracked;
    object.final_label = history.labels.back().second;
    ++summary.confusion[row][static_cast<int>(*object.final_label)];
    object.correct = *object.final_label == history.true_class;
    if (object.correct) {
      ++correct;
      // The first matched scan after the last wrong label (or the first matched scan at all).
      size_t settled = 0;
      for (size_t k = 0; k < history.labels.size(); ++k) {
        if (history.labels[k].second != history.true_class) settled = k + 1;
      }
      const int64_t settled_utime = history.labels[settled].first;
      const double delay_s =
          SecondsBetween(settled_utime, history.first_visible_utime);
      object.delay_s = delay_s;
      int64_t visible_before = 0;
      for (int64_t t : history.visible_utimes) visible_before += t < settled_utime ? 1 : 0;
      object.visible_scans_until_right = visible_before;
      visible_scans_sum += visible_before;
      delay_sum_s += delay_s;
      ++num_delays;
      summary.max_delay_s = std::max(summary.max_delay_s.value_or(0.0), delay_s);
    }
    summary.objects.push_back(object);
  }
  for (int64_t id : seen_standing_) {
    if (histories_.count(id) == 0) summary.movers_seen_only_standing.push_back(id);
  }
  if (!histories_.empty()) {
    summary.accuracy = static_cast<double>(correct) / static_cast<double>(histories_.size());
  }
  if (tracked > 0) {
    summary.accuracy_of_tracked = static_cast<double>(correct) / static_cast<double>(tracked);
  }
  if (num_delays > 0) {
    summary.mean_delay_s = delay_sum_s / static_cast<double>(num_delays);
    summary.mean_visible_scans_until_right =
        static_cast<double>(visible_scans_sum) / static_cast<double>(num_delays);
  }
  return summary;
}

}  // namespace slammtt
