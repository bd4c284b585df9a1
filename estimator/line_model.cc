#include "estimator/line_model.h"

#include <cmath>

#include "estimator/angle.h"

namespace slammtt {

Eigen::Vector2d PredictLineObservation(const Eigen::Vector3d& robot_pose,
                                       const Eigen::Vector2d& line, const SensorMount& mount,
                                       Eigen::Matrix<double, 2, 3>* jacobian_robot,
                                       Eigen::Matrix2d* jacobian_line, bool* flipped) {
  Eigen::Matrix<double, 2, 3> ds;
  const Eigen::Vector2d s = SensorPosition(robot_pose, mount, &ds);
  const Eigen::Vector2d n(std::cos(line(1)), std::sin(line(1)));
  const Eigen::Vector2d dn(-n(1), n(0));  // d n / d alpha
  double rho_s = line(0) - s.dot(n);
  double alpha_s = line(1) - robot_pose(2) - mount.yaw_rad;
  const double sign = rho_s < 0.0 ? -1.0 : 1.0;
  if (sign < 0.0) {
    rho_s = -rho_s;
    alpha_s += M_PI;
  }
  if (flipped != nullptr) *flipped = sign < 0.0;
  if (jacobian_robot != nullptr) {
    jacobian_robot->row(0) = -sign * n.transpose() * ds;
    jacobian_robot->row(1) << 0.0, 0.0, -1.0;
  }
  if (jacobian_line != nullptr) {
    *jacobian_line << sign * 1.0, -sign * s.dot(dn), 0.0, 1.0;
  }
  return Eigen::Vector2d(rho_s, WrapAngle(alpha_s));
}

Eigen::Vector2d LineFromObservation(const Eigen::Vector3d& robot_pose,
                                    const Eigen::Vector2d& observation, const SensorMount& mount,
                                    Eigen::Matrix<double, 2, 3>* jacobian_robot,
                                    Eigen::Matrix2d* jacobian_observation) {
  Eigen::Matrix<double, 2, 3> ds;
  const Eigen::Vector2d s = SensorPosition(robot_pose, mount, &ds);
  const double alpha = observation(1) + robot_pose(2) + mount.yaw_rad;
  const Eigen::Vector2d n(std::cos(alpha), std::sin(alpha));
  const Eigen::Vector2d dn(-n(1), n(0));
  const double rho = observation(0) + s.dot(n);
  if (jacobian_robot != nullptr) {
    // rho depends on the pose through s and through alpha (the heading).
    jacobian_robot->row(0) = n.transpose() * ds;
    (*jacobian_robot)(0, 2) += s.dot(dn);
    jacobian_robot->row(1) << 0.0, 0.0, 1.0;
  }
  if (jacobian_observation != nullptr) {
    *jacobian_observation << 1.0, s.dot(dn), 0.0, 1.0;
  }
  return Eigen::Vector2d(rho, WrapAngle(alpha));
}

Eigen::Vector2d SensorPointToMap(const Eigen::Vector3d& robot_pose, const SensorMount& mount,
                                 const Eigen::Vector2d& sensor_point) {
  const Eigen::Vector2d s = SensorPosition(robot_pose, mount);
  const double c = std::cos(robot_pose(2) + mount.yaw_rad);
  const double n = std::sin(robot_pose(2) + mount.yaw_rad);
  return s + Eigen::Vector2d(c * sensor_point(0) - n * sensor_point(1),
                             n * sensor_point(0) + c * sensor_point(1));
}

double PositionAlongLine(const Eigen::Vector2d& line, const Eigen::Vector2d& point) {
  return -std::sin(line(1)) * point(0) + std::cos(line(1)) * point(1);
}

Eigen::Vector2d PointOnLine(const Eigen::Vector2d& line, double t) {
  const Eigen::Vector2d n(std::cos(line(1)), std::sin(line(1)));
  return line(0) * n + t * Eigen::Vector2d(-n(1), n(0));
}

}  // namespace slammtt
