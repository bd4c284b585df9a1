#include "tools/metrics/trajectory_error.h"

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

}  // namespace slammtt
