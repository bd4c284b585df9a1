#include "tools/metrics/pose2.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "common/utime.h"

namespace slammtt {

Pose2 Compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.heading_rad);
  const double s = std::sin(a.heading_rad);
  return Pose2{a.x_m + c * b.x_m - s * b.y_m, a.y_m + s * b.x_m + c * b.y_m,
               WrapAngle(a.heading_rad + b.heading_rad)};
}

Pose2 Inverse(const Pose2& pose) {
  const double c = std::cos(pose.heading_rad);
  const double s = std::sin(pose.heading_rad);
  return Pose2{-c * pose.x_m - s * pose.y_m, s * pose.x_m - c * pose.y_m,
               WrapAngle(-pose.heading_rad)};
}

Eigen::Vector2d TransformPoint(const Pose2& pose, const Eigen::Vector2d& point) {
  return Eigen::Vector2d(pose.x_m, pose.y_m) + RotateVector(pose, point);
}

Eigen::Vector2d RotateVector(const Pose2& pose, const Eigen::Vector2d& vector) {
  const double c = std::cos(pose.heading_rad);
  const double s = std::sin(pose.heading_rad);
  return Eigen::Vector2d(c * vector.x() - s * vector.y(), s * vector.x() + c * vector.y());
}

Eigen::Matrix2d RotateCovariance(const Pose2& pose, const Eigen::Matrix2d& covariance) {
  const double c = std::cos(pose.heading_rad);
  const double s = std::sin(pose.heading_rad);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  return rotation * covariance * rotation.transpose();
}

Pose2 AnchorTransform(const Pose2& truth, const Pose2& estimate) {
  return Compose(truth, Inverse(estimate));
}

std::optional<Pose2> InterpolatePose(const std::vector<TimedPose>& trajectory, int64_t utime) {
  if (trajectory.empty() || utime < trajectory.front().utime ||
      utime > trajectory.back().utime) {
    return std::nullopt;
  }
  const auto after = std::lower_bound(
      trajectory.begin(), trajectory.end(), utime,
      [](const TimedPose& sample, int64_t t) { return sample.utime < t; });
  if (after->utime == utime) return after->pose;
  const TimedPose& b = *after;
  const TimedPose& a = *(after - 1);
  const double f = MicrosecondsBetween(utime, a.utime) / MicrosecondsBetween(b.utime, a.utime);
  return Pose2{a.pose.x_m + f * (b.pose.x_m - a.pose.x_m),
               a.pose.y_m + f * (b.pose.y_m - a.pose.y_m),
               WrapAngle(a.pose.heading_rad +
                         f * WrapAngle(b.pose.heading_rad - a.pose.heading_rad))};
}

}  // namespace slammtt
