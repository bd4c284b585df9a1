#include "tools/metrics/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slammtt {
namespace {

bool Finite(const Pose2& p) {
  return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.heading_rad);
}

}  // namespace

TrajectoryError EvaluateTrajectory(const std::vector<PosePair>& pairs) {
  TrajectoryError error;
  double sum_sq = 0.0;
  double sum = 0.0;
  double heading_sum_sq = 0.0;
  for (const PosePair& pair : pairs) {
    if (!Finite(pair.truth) || !Finite(pair.estimate)) {
      throw std::invalid_argument("trajectory error: non-finite pose at utime " +
                                  std::to_string(pair.utime));
    }
    const double e = std::hypot(pair.estimate.x_m - pair.truth.x_m,
                                pair.estimate.y_m - pair.truth.y_m);
    const double h = WrapAngle(pair.estimate.heading_rad - pair.truth.heading_rad);
    error.utime.push_back(pair.utime);
    error.position_error_m.push_back(e);
    error.heading_error_rad.push_back(h);
    sum_sq += e * e;
    sum += e;
    heading_sum_sq += h * h;
    if (error.count == 0 || e > error.max_m) {
      error.max_m = e;
      error.max_utime = pair.utime;
    }
    ++error.count;
  }
  if (error.count > 0) {
    const double n = static_cast<double>(error.count);
    error.rmse_m = std::sqrt(sum_sq / n);
    error.mean_m = sum / n;
    error.heading_rmse_rad = std::sqrt(heading_sum_sq / n);
    error.final_position_error_m = error.position_error_m.back();
    error.final_heading_error_rad = error.heading_error_rad.back();
  }
  return error;
}

Pose2 AnchorAtFirstPair(std::vector<PosePair>* pairs) {
  if (pairs->empty()) return Pose2{};
  const Pose2 anchor = AnchorTransform(pairs->front().truth, pairs->front().estimate);
  for (PosePair& pair : *pairs) pair.estimate = Compose(anchor, pair.estimate);
  return anchor;
}

Pose2 LeastSquaresAlignment(const std::vector<PosePair>& pairs) {
  if (pairs.size() < 2) return Pose2{};
  Eigen::Vector2d truth_mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d estimate_mean = Eigen::Vector2d::Zero();
  for (const PosePair& p : pairs) {
    truth_mean += Eigen::Vector2d(p.truth.x_m, p.truth.y_m);
    estimate_mean += Eigen::Vector2d(p.estimate.x_m, p.estimate.y_m);
  }
  truth_mean /= static_cast<double>(pairs.size());
  estimate_mean /= static_cast<double>(pairs.size());
  // The rotation maximises sum t'^T R e' over the centred points: its angle is the direction of
  // (sum e' . t', sum e' x t').
  double dot = 0.0;
  double cross = 0.0;
  for (const PosePair& p : pairs) {
    const Eigen::Vector2d t = Eigen::Vector2d(p.truth.x_m, p.truth.y_m) - truth_mean;
    const Eigen::Vector2d e = Eigen::Vector2d(p.estimate.x_m, p.estimate.y_m) - estimate_mean;
    dot += e.dot(t);
    cross += e.x() * t.y() - e.y() * t.x();
  }
  const double angle = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
  const Pose2 rotation{0.0, 0.0, angle};
  const Eigen::Vector2d translation = truth_mean - RotateVector(rotation, estimate_mean);
  return Pose2{translation.x(), translation.y(), angle};
}

RelativePoseError EvaluateRelativePoseError(const std::vector<PosePair>& pairs) {
  RelativePoseError rpe;
  double translation_sq = 0.0;
  double translation_sum = 0.0;
  double rotation_sq = 0.0;
  for (size_t i = 0; i + 1 < pairs.size(); ++i) {
    const Pose2 truth_step = Compose(Inverse(pairs[i].truth), pairs[i + 1].truth);
    const Pose2 estimate_step = Compose(Inverse(pairs[i].estimate), pairs[i + 1].estimate);
    const Pose2 e = Compose(Inverse(truth_step), estimate_step);
    const double t = std::hypot(e.x_m, e.y_m);
    const double r = WrapAngle(e.heading_rad);
    translation_sq += t * t;
    translation_sum += t;
    rotation_sq += r * r;
    rpe.translation_max_m = std::max(rpe.translation_max_m, t);
    ++rpe.count;
  }
  if (rpe.count > 0) {
    const double n = static_cast<double>(rpe.count);
    rpe.translation_rmse_m = std::sqrt(translation_sq / n);
    rpe.translation_mean_m = translation_sum / n;
    rpe.rotation_rmse_rad = std::sqrt(rotation_sq / n);
  }
  return rpe;
}

}  // namespace slammtt
