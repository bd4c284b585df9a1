// Score of the estimator's final static map against the true static objects, and the count of
// moving objects that were mapped as static (the failure of plain EKF-SLAM in a dynamic world
// that the paper shows in its Fig. 5). Definitions in docs/evaluation.md:
//
// - matching: Hungarian assignment of map landmarks to the true static objects that were ever
//   visible, minimum total distance among the assignments with the most pairs within the
//   threshold (distance <= threshold);
// - static_recall = matched / ever-visible static objects; landmark RMSE over matched pairs;
// - a mover in the static map: a landmark not matched to a static object that lies within the
//   threshold of some moving object's true path (the polyline through its true positions).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "tools/metrics/clear_mot.h"

namespace slammtt {

struct MapScore {
  int num_landmarks = 0;
  int num_static_truth = 0;
  int num_matched = 0;
  int num_movers_in_static_map = 0;
  int num_unexplained = 0;  // neither a static object nor near a mover's path
  std::optional<double> static_recall;    // absent without any ever-visible static object
  std::optional<double> landmark_rmse_m;  // absent without any match
  double landmark_max_error_m = 0.0;
  std::vector<std::pair<int64_t, int64_t>> matches;  // (landmark id, truth id)
  std::vector<int64_t> mover_landmarks;              // ids of landmarks on a mover's path
  std::vector<int64_t> unexplained_landmarks;
};

// `landmarks` and `static_truth` in one frame; each path of `mover_paths` is a sequence of true
// positions in time order (a single point is a path too). std::invalid_argument on non-finite
// input or a threshold that is not positive.
MapScore ScoreMap(const std::vector<IdentifiedPoint>& landmarks,
                  const std::vector<IdentifiedPoint>& static_truth,
                  const std::vector<std::vector<Eigen::Vector2d>>& mover_paths,
                  double match_threshold_m);

// Distance from a point to a polyline (to its only point when it has one; infinity when empty).
double DistanceToPath(const Eigen::Vector2d& point, const std::vector<Eigen::Vector2d>& path);

}  // namespace slammtt
