#include "geometry/pose2.h"

#include <cmath>

#include "common/angle.h"

namespace slammtt {

Eigen::Vector3d ComposePoses(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::cos(a(2));
  const double s = std::sin(a(2));
  return Eigen::Vector3d(a(0) + c * b(0) - s * b(1), a(1) + s * b(0) + c * b(1),
                         WrapAngle(a(2) + b(2)));
}

Eigen::Vector3d PoseBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            Eigen::Matrix3d* jacobian_a, Eigen::Matrix3d* jacobian_b) {
  const double c = std::cos(a(2));
  const double s = std::sin(a(2));
  const double dx = b(0) - a(0);
  const double dy = b(1) - a(1);
  // R(a)^T (t_b - t_a), theta_b - theta_a.
  const Eigen::Vector3d between(c * dx + s * dy, -s * dx + c * dy, WrapAngle(b(2) - a(2)));
  if (jacobian_a != nullptr) {
    *jacobian_a << -c, -s, between(1),  //
        s, -c, -between(0),             //
        0.0, 0.0, -1.0;
  }
  if (jacobian_b != nullptr) {
    *jacobian_b << c, s, 0.0,  //
        -s, c, 0.0,            //
        0.0, 0.0, 1.0;
  }
  return between;
}

Eigen::Vector3d PoseLogarithm(const Eigen::Vector3d& motion, Eigen::Matrix3d* jacobian) {
  const double theta = motion(2);
  // a(theta) = (theta / 2) cot(theta / 2) and its derivative; below 1e-3 rad the Taylor series
  // (a = 1 - theta^2 / 12 - theta^4 / 720) is exact to rounding where the closed form cancels.
  double a;
  double a_prime;
  if (std::abs(theta) < 1e-3) {
    const double theta2 = theta * theta;
    a = 1.0 - theta2 / 12.0 - theta2 * theta2 / 720.0;
    a_prime = -theta / 6.0 - theta2 * theta / 180.0;
  } else {
    const double half = 0.5 * theta;
    const double sin_half = std::sin(half);
    const double cot_half = std::cos(half) / sin_half;
    a = half * cot_half;
    a_prime = 0.5 * cot_half - 0.25 * theta / (sin_half * sin_half);
  }
  const double b = 0.5 * theta;
  const double x = motion(0);
  const double y = motion(1);
  if (jacobian != nullptr) {
    *jacobian << a, b, a_prime * x + 0.5 * y,  //
        -b, a, -0.5 * x + a_prime * y,         //
        0.0, 0.0, 1.0;
  }
  return Eigen::Vector3d(a * x + b * y, -b * x + a * y, theta);
}

Eigen::Vector3d RetractPose(const Eigen::Vector3d& pose, const Eigen::Vector3d& delta) {
  return Eigen::Vector3d(pose(0) + delta(0), pose(1) + delta(1), WrapAngle(pose(2) + delta(2)));
}

Eigen::Vector3d PoseExponential(const Eigen::Vector3d& twist) {
  const double omega = twist(2);
  double s;  // sin(omega) / omega
  double c;  // (1 - cos(omega)) / omega
  if (std::abs(omega) < 1e-3) {
    // Series to the omega^4 terms: exact to rounding where the closed forms cancel.
    const double omega2 = omega * omega;
    s = 1.0 - omega2 / 6.0 + omega2 * omega2 / 120.0;
    c = omega / 2.0 - omega2 * omega / 24.0;
  } else {
    s = std::sin(omega) / omega;
    c = (1.0 - std::cos(omega)) / omega;
  }
  return Eigen::Vector3d(s * twist(0) - c * twist(1), c * twist(0) + s * twist(1),
                         WrapAngle(omega));
}

Eigen::Vector3d RetractPoseExponential(const Eigen::Vector3d& pose, const Eigen::Vector3d& delta) {
  return ComposePoses(pose, PoseExponential(delta));
}

Eigen::Matrix3d RetractionJacobianAtZero(double theta) {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  Eigen::Matrix3d jacobian;
  jacobian << c, -s, 0.0,  //
      s, c, 0.0,           //
      0.0, 0.0, 1.0;
  return jacobian;
}

}  // namespace slammtt
