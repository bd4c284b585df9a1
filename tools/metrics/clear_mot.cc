#include "tools/metrics/clear_mot.h"

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "tools/metrics/assignment.h"

namespace slammtt {
namespace {

void CheckUniqueFinite(const std::vector<IdentifiedPoint>& points, const char* what) {
  std::set<int64_t> ids;
  for (const IdentifiedPoint& p : points) {
    if (!ids.insert(p.id).second) {
      throw std::invalid_argument(std::string("CLEAR-MOT: duplicate ") + what + " id " +
                                  std::to_string(p.id));
    }
    if (!p.position_m.allFinite()) {
      throw std::invalid_argument(std::string("CLEAR-MOT: non-finite ") + what + " position");
    }
  }
}

}  // namespace

ClearMotAccumulator::ClearMotAccumulator(double match_threshold_m)
    : threshold_m_(match_threshold_m) {
  if (!(match_threshold_m > 0.0) || !std::isfinite(match_threshold_m)) {
    throw std::invalid_argument("CLEAR-MOT: match threshold must be a positive number");
  }
}

ClearMotFrame ClearMotAccumulator::AddFrame(const std::vector<IdentifiedPoint>& truth,
                                            const std::vector<IdentifiedPoint>& hypotheses,
                                            const DontCare& dont_care) {
  CheckUniqueFinite(truth, "truth");
  CheckUniqueFinite(hypotheses, "hypothesis");
  CheckUniqueFinite(dont_care.objects, "don't-care object");
  for (const IdentifiedPoint& object : dont_care.objects) {
    for (const IdentifiedPoint& t : truth) {
      if (t.id == object.id) {
        throw std::invalid_argument("CLEAR-MOT: object " + std::to_string(t.id) +
                                    " is both in the truth set and a don't-care object");
      }
    }
  }
  for (const Eigen::Vector2d& p : dont_care.positions) {
    if (!p.allFinite()) throw std::invalid_argument("CLEAR-MOT: non-finite don't-care position");
  }
  const int64_t frame_index = totals_.num_frames;
  ClearMotFrame frame;
  frame.num_truth = static_cast<int>(truth.size());
  frame.num_hypotheses = static_cast<int>(hypotheses.size());

  std::map<int64_t, size_t> hypothesis_index;
  for (size_t j = 0; j < hypotheses.size(); ++j) hypothesis_index[hypotheses[j].id] = j;
  std::vector<int> truth_to_hyp(truth.size(), -1);
  std::vector<bool> hyp_taken(hypotheses.size(), false);
  auto distance = [&](size_t i, size_t j) {
    return (truth[i].position_m - hypotheses[j].position_m).norm();
  };

  // Step 1: carry over the last correspondences that still hold.
  for (size_t i = 0; i < truth.size(); ++i) {
    const auto history = objects_.find(truth[i].id);
    if (history == objects_.end() || !history->second.last_hypothesis) continue;
    const int64_t hyp_id = *history->second.last_hypothesis;
    const auto it = hypothesis_index.find(hyp_id);
    if (it == hypothesis_index.end()) continue;
    if (last_object_of_hypothesis_.at(hyp_id) != truth[i].id) continue;
    if (distance(i, it->second) > threshold_m_) continue;
    truth_to_hyp[i] = static_cast<int>(it->second);
    hyp_taken[it->second] = true;
  }

  // Step 2: optimal assignment of the rest.
  std::vector<size_t> free_truth;
  std::vector<size_t> free_hyp;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (truth_to_hyp[i] < 0) free_truth.push_back(i);
  }
  for (size_t j = 0; j < hypotheses.size(); ++j) {
    if (!hyp_taken[j]) free_hyp.push_back(j);
  }
  Eigen::MatrixXd cost(free_truth.size(), free_hyp.size());
  for (size_t a = 0; a < free_truth.size(); ++a) {
    for (size_t b = 0; b < free_hyp.size(); ++b) {
      const double d = distance(free_truth[a], free_hyp[b]);
      cost(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
          d <= threshold_m_ ? d : kForbiddenCost;
    }
  }
  const Assignment assignment = SolveMinCostAssignment(cost);
  for (size_t a = 0; a < free_truth.size(); ++a) {
    const int b = assignment.row_to_col[a];
    if (b < 0) continue;
    const size_t i = free_truth[a];
    const size_t j = free_hyp[static_cast<size_t>(b)];
    truth_to_hyp[i] = static_cast<int>(j);
    hyp_taken[j] = true;
    // Step 3: a new correspondence that contradicts the last one is an identity switch.
    const auto history = objects_.find(truth[i].id);
    if (history != objects_.end() && history->second.last_hypothesis &&
        *history->second.last_hypothesis != hypotheses[j].id) {
      ++frame.num_id_switches;
      frame.id_switches.push_back(
          {truth[i].id, *history->second.last_hypothesis, hypotheses[j].id});
    }
  }

  // Bookkeeping: matches, misses, fragmentations.
  for (size_t i = 0; i < truth.size(); ++i) {
    ObjectHistory& history = objects_[truth[i].id];
    const int j = truth_to_hyp[i];
    if (j < 0) {
      ++frame.num_misses;
      if (history.ever_tracked && !history.interrupted) {
        history.interrupted = true;
        history.interrupted_since_frame = frame_index;
      }
      continue;
    }
    const IdentifiedPoint& hyp = hypotheses[static_cast<size_t>(j)];
    ++frame.num_matches;
    frame.distance_sum_m += distance(i, static_cast<size_t>(j));
    frame.matches.emplace_back(truth[i].id, hyp.id);
    if (history.ever_tracked && history.interrupted) {
      ++frame.num_fragmentations;
      frame.fragmentations.push_back(
          {truth[i].id, *history.last_hypothesis, hyp.id, history.interrupted_since_frame});
    }
    history.ever_tracked = true;
    history.interrupted = false;
    history.last_hypothesis = hyp.id;
    last_object_of_hypothesis_[hyp.id] = truth[i].id;
  }

  // Step 4: unmatched hypotheses are false positives unless excused: first one each by the
  // don't-care objects (optimal assignment), then any near a don't-care position.
  std::vector<size_t> unmatched;
  for (size_t j = 0; j < hypotheses.size(); ++j) {
    if (!hyp_taken[j]) unmatched.push_back(j);
  }
  std::vector<bool> excused(hypotheses.size(), false);
  Eigen::MatrixXd dont_care_cost(dont_care.objects.size(), unmatched.size());
  for (size_t a = 0; a < dont_care.objects.size(); ++a) {
    for (size_t b = 0; b < unmatched.size(); ++b) {
      const double d =
          (dont_care.objects[a].position_m - hypotheses[unmatched[b]].position_m).norm();
      dont_care_cost(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
          d <= threshold_m_ ? d : kForbiddenCost;
    }
  }
  const Assignment dont_care_assignment = SolveMinCostAssignment(dont_care_cost);
  for (size_t a = 0; a < dont_care.objects.size(); ++a) {
    const int b = dont_care_assignment.row_to_col[a];
    if (b < 0) continue;
    excused[unmatched[static_cast<size_t>(b)]] = true;
    ++frame.num_dont_care_objects;
  }
  for (size_t j : unmatched) {
    if (excused[j]) continue;
    for (const Eigen::Vector2d& p : dont_care.positions) {
      if ((p - hypotheses[j].position_m).norm() <= threshold_m_) excused[j] = true;
    }
    if (excused[j]) ++frame.num_dont_care_positions;
  }
  for (size_t j : unmatched) {
    if (excused[j]) {
      ++frame.num_dont_care;
      frame.dont_care_hypotheses.push_back(hypotheses[j].id);
    } else {
      ++frame.num_false_positives;
    }
  }

  ++totals_.num_frames;
  totals_.num_truth += frame.num_truth;
  totals_.num_matches += frame.num_matches;
  totals_.num_misses += frame.num_misses;
  totals_.num_false_positives += frame.num_false_positives;
  totals_.num_id_switches += frame.num_id_switches;
  totals_.num_fragmentations += frame.num_fragmentations;
  totals_.num_dont_care += frame.num_dont_care;
  totals_.num_dont_care_objects += frame.num_dont_care_objects;
  totals_.num_dont_care_positions += frame.num_dont_care_positions;
  totals_.distance_sum_m += frame.distance_sum_m;
  return frame;
}

ClearMotSummary ClearMotAccumulator::Summary() const {
  ClearMotSummary summary = totals_;
  if (summary.num_truth > 0) {
    summary.mota = 1.0 - static_cast<double>(summary.num_misses + summary.num_false_positives +
                                             summary.num_id_switches) /
                             static_cast<double>(summary.num_truth);
  }
  if (summary.num_matches > 0) {
    summary.motp_m = summary.distance_sum_m / static_cast<double>(summary.num_matches);
  }
  return summary;
}

}  // namespace slammtt
