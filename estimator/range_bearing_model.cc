#include "estimator/range_bearing_model.h"

#include <cmath>

#include "estimator/angle.h"

namespace slammtt {

Eigen::Vector2d SensorPosition(const Eigen::Vector3d& robot_pose, const SensorMount& mount,
                               Eigen::Matrix<double, 2, 3>* jacobian_robot) {
  const double c = std::cos(robot_pose(2));
  const double s = std::sin(robot_pose(2));
  const double a = mount.forward_m;
  const double b = mount.left_m;
  if (jacobian_robot != nullptr) {
    *jacobian_robot << 1.0, 0.0, -a * s - b * c,  //
        0.0, 1.0, a * c - b * s;
  }
  return Eigen::Vector2d(robot_pose(0) + a * c - b * s, robot_pose(1) + a * s + b * c);
}

Eigen::Vector2d PredictRangeBearing(const Eigen::Vector3d& robot_pose,
                                    const Eigen::Vector2d& point, const SensorMount& mount,
                                    Eigen::Matrix<double, 2, 3>* jacobian_robot,
                                    Eigen::Matrix2d* jacobian_point) {
  Eigen::Matrix<double, 2, 3> sensor_jacobian;
  const Eigen::Vector2d sensor = SensorPosition(robot_pose, mount, &sensor_jacobian);
  const double dx = point(0) - sensor(0);
  const double dy = point(1) - sensor(1);
  const double q = dx * dx + dy * dy;
  const double r = std::sqrt(q);
  // d(r, theta)/d(point) for the offset from the sensor; d/d(sensor) is its negative.
  Eigen::Matrix2d wrt_point;
  wrt_point << dx / r, dy / r,  //
      -dy / q, dx / q;
  if (jacobian_point != nullptr) *jacobian_point = wrt_point;
  if (jacobian_robot != nullptr) {
    *jacobian_robot = -wrt_point * sensor_jacobian;
    (*jacobian_robot)(1, 2) -= 1.0;  // theta = ... - phi - psi
  }
  return Eigen::Vector2d(r, WrapAngle(std::atan2(dy, dx) - robot_pose(2) - mount.yaw_rad));
}

Eigen::Vector2d PointFromRangeBearing(const Eigen::Vector3d& robot_pose,
                                      const Eigen::Vector2d& range_bearing,
                                      const SensorMount& mount,
                                      Eigen::Matrix<double, 2, 3>* jacobian_robot,
                                      Eigen::Matrix2d* jacobian_measurement) {
  Eigen::Matrix<double, 2, 3> sensor_jacobian;
  const Eigen::Vector2d sensor = SensorPosition(robot_pose, mount, &sensor_jacobian);
  const double r = range_bearing(0);
  const double angle = robot_pose(2) + mount.yaw_rad + range_bearing(1);
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  if (jacobian_robot != nullptr) {
    *jacobian_robot = sensor_jacobian;
    (*jacobian_robot)(0, 2) += -r * s;
    (*jacobian_robot)(1, 2) += r * c;
  }
  if (jacobian_measurement != nullptr) {
    *jacobian_measurement << c, -r * s,  //
        s, r * c;
  }
  return Eigen::Vector2d(sensor(0) + r * c, sensor(1) + r * s);
}

}  // namespace slammtt
