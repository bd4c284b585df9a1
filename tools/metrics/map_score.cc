#include "tools/metrics/map_score.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tools/metrics/assignment.h"

namespace slammtt {

double DistanceToPath(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& path) {
  double best = std::numeric_limits<double>::infinity();
  if (path.size() == 1) return (point - path.front()).norm();
  for (size_t k = 1; k < path.size(); ++k) {
    const Eigen::Vector2d a = path[k - 1];
    const Eigen::Vector2d ab = path[k] - a;
    const double length_sq = ab.squaredNorm();
    double f = length_sq > 0.0 ? (point - a).dot(ab) / length_sq : 0.0;
    f = std::clamp(f, 0.0, 1.0);
    best = std::min(best, (point - (a + f * ab)).norm());
  }
  return best;
}

MapScore ScoreMap(const std::vector<IdentifiedPoint>& landmarks,
                  const std::vector<IdentifiedPoint>& static_truth,
                  const std::vector<std::vector<Eigen::Vector2d>>& mover_paths,
                  double match_threshold_m) {
  if (!(match_threshold_m > 0.0) || !std::isfinite(match_threshold_m)) {
    throw std::invalid_argument("map score: match threshold must be a positive number");
  }
  for (const auto* set : {&landmarks, &static_truth}) {
    for (const IdentifiedPoint& p : *set) {
      if (!p.position_m.allFinite()) throw std::invalid_argument("map score: non-finite point");
    }
  }
  for (const auto& path : mover_paths) {
    for (const Eigen::Vector2d& p : path) {
      if (!p.allFinite()) throw std::invalid_argument("map score: non-finite path point");
    }
  }

  MapScore score;
  score.num_landmarks = static_cast<int>(landmarks.size());
  score.num_static_truth = static_cast<int>(static_truth.size());
  Eigen::MatrixXd cost(landmarks.size(), static_truth.size());
  for (size_t i = 0; i < landmarks.size(); ++i) {
    for (size_t j = 0; j < static_truth.size(); ++j) {
      const double d = (landmarks[i].position_m - static_truth[j].position_m).norm();
      cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          d <= match_threshold_m ? d : kForbiddenCost;
    }
  }
  const Assignment assignment = SolveMinCostAssignment(cost);
  double sum_sq = 0.0;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const int j = assignment.row_to_col[i];
    if (j >= 0) {
      const double d = cost(static_cast<Eigen::Index>(i), j);
      sum_sq += d * d;
      score.landmark_max_error_m = std::max(score.landmark_max_error_m, d);
      score.matches.emplace_back(landmarks[i].id, static_truth[static_cast<size_t>(j)].id);
      continue;
    }
    bool on_mover_path = false;
    for (const auto& path : mover_paths) {
      if (!path.empty() && DistanceToPath(landmarks[i].position_m, path) <= match_threshold_m) {
        on_mover_path = true;
      }
    }
    if (on_mover_path) {
      score.mover_landmarks.push_back(landmarks[i].id);
    } else {
      score.unexplained_landmarks.push_back(landmarks[i].id);
    }
  }
  score.num_matched = assignment.num_assigned;
  score.num_movers_in_static_map = static_cast<int>(score.mover_landmarks.size());
  score.num_unexplained = static_cast<int>(score.unexplained_landmarks.size());
  if (score.num_static_truth > 0) {
    score.static_recall =
        static_cast<double>(score.num_matched) / static_cast<double>(score.num_static_truth);
  }
  if (score.num_matched > 0) {
    score.landmark_rmse_m = std::sqrt(sum_sq / static_cast<double>(score.num_matched));
  }
  return score;
}

}  // namespace slammtt
