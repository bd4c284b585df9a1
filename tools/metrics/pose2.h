// Planar rigid poses for evaluation: composing, inverting, applying to points, interpolating a
// timed trajectory, and the anchoring of an estimate's frame to the truth.
//
// Frames follow docs/DEVELOPING.md: x forward, y left, angles CCW, headings wrapped to (-pi, pi].
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <vector>

#include "common/angle.h"  // WrapAngle

namespace slammtt {

struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;
};

// a * b: the pose b, given in the frame of a, expressed in a's parent frame.
Pose2 Compose(const Pose2& a, const Pose2& b);
Pose2 Inverse(const Pose2& pose);
// A point given in the frame of `pose`, expressed in the parent frame.
Eigen::Vector2d TransformPoint(const Pose2& pose, const Eigen::Vector2d& point);
// A free vector (velocity) rotated into the parent frame.
Eigen::Vector2d RotateVector(const Pose2& pose, const Eigen::Vector2d& vector);
// 2x2 covariance of a point rotated into the parent frame (R C R^T).
Eigen::Matrix2d RotateCovariance(const Pose2& pose, const Eigen::Matrix2d& covariance);

// The rigid transform that takes the estimate's frame onto the truth's frame so that the two
// coincide at one moment: anchor * estimate = truth (no fitting; docs/evaluation.md).
Pose2 AnchorTransform(const Pose2& truth, const Pose2& estimate);

struct TimedPose {
  int64_t utime = 0;
  Pose2 pose;
};

// The pose at `utime` by linear interpolation of position and shortest-arc interpolation of
// heading between the two neighbouring samples of `trajectory` (sorted by utime, unique times).
// nullopt before the first or after the last sample: no extrapolation.
std::optional<Pose2> InterpolatePose(const std::vector<TimedPose>& trajectory, int64_t utime);

}  // namespace slammtt
