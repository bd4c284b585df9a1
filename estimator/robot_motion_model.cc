#include "estimator/robot_motion_model.h"

#include <algorithm>
#include <cmath>

#include "estimator/angle.h"

namespace slammtt {

Eigen::Vector3d PredictRobotPose(const Eigen::Vector3d& pose, const OdometryIncrement& increment,
                                 Eigen::Matrix3d* jacobian_pose,
                                 Eigen::Matrix<double, 3, 2>* jacobian_increment) {
  const double d = increment.distance_m;
  const double heading_after = pose(2) + increment.rotation_rad;
  const double c = std::cos(heading_after);
  const double s = std::sin(heading_after);
  if (jacobian_pose != nullptr) {
    *jacobian_pose << 1.0, 0.0, -d * s,  //
        0.0, 1.0, d * c,                 //
        0.0, 0.0, 1.0;
  }
  if (jacobian_increment != nullptr) {
    *jacobian_increment << c, -d * s,  //
        s, d * c,                      //
        0.0, 1.0;
  }
  return Eigen::Vector3d(pose(0) + d * c, pose(1) + d * s, WrapAngle(heading_after));
}

Eigen::Vector3d PredictRobotPoseWithHeadingDrift(const Eigen::Vector3d& pose,
                                                 double heading_drift_rad_per_m,
                                                 const OdometryIncrement& increment,
                                                 Eigen::Matrix4d* jacobian_robot,
                                                 Eigen::Matrix<double, 4, 2>* jacobian_increment) {
  const double d = increment.distance_m;
  const double b = heading_drift_rad_per_m;
  const OdometryIncrement corrected{d, increment.rotation_rad + b * d};
  Eigen::Matrix3d f;
  Eigen::Matrix<double, 3, 2> g;
  const Eigen::Vector3d new_pose = PredictRobotPose(pose, corrected, &f, &g);
  // Chain rule through the corrected rotation delta + b d: d/db = d * (d/d delta), and the
  // distance enters twice, d/dd = (d/dd) + b * (d/d delta).
  if (jacobian_robot != nullptr) {
    jacobian_robot->setZero();
    jacobian_robot->topLeftCorner<3, 3>() = f;
    jacobian_robot->block<3, 1>(0, 3) = d * g.col(1);
    (*jacobian_robot)(3, 3) = 1.0;
  }
  if (jacobian_increment != nullptr) {
    jacobian_increment->setZero();
    jacobian_increment->block<3, 1>(0, 0) = g.col(0) + b * g.col(1);
    jacobian_increment->block<3, 1>(0, 1) = g.col(1);
  }
  return new_pose;
}

OdometryIncrement IncrementBetweenOdometryPoses(const Eigen::Vector3d& from,
                                                const Eigen::Vector3d& to) {
  OdometryIncrement increment;
  increment.rotation_rad = WrapAngle(to(2) - from(2));
  const double dx = to(0) - from(0);
  const double dy = to(1) - from(1);
  const double length = std::hypot(dx, dy);
  const double along = dx * std::cos(to(2)) + dy * std::sin(to(2));
  increment.distance_m = along < 0.0 ? -length : length;
  return increment;
}

Eigen::Matrix2d OdometryIncrementCovariance(const OdometryIncrement& increment, double dt_s,
                                            const OdometryNoiseOptions& noise) {
  const double distance = std::abs(increment.distance_m);
  const double rotation = std::abs(increment.rotation_rad);
  const double dt = std::max(0.0, dt_s);
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  covariance(0, 0) = noise.distance_var_per_m * distance + noise.distance_var_per_s * dt;
  covariance(1, 1) = noise.rotation_var_per_rad * rotation + noise.rotation_var_per_m * distance +
                     noise.rotation_var_per_s * dt;
  return covariance;
}

void VisitOdometryNoiseOptions(OptionVisitor* v, OdometryNoiseOptions* n) {
  using R = OptionRange;
  v->Double("distance_var_per_m", &n->distance_var_per_m, R::AtLeast(0),
            "odometry distance variance [m^2] per metre travelled");
  v->Double("rotation_var_per_rad", &n->rotation_var_per_rad, R::AtLeast(0),
            "odometry rotation variance [rad^2] per radian turned");
  v->Double("rotation_var_per_m", &n->rotation_var_per_m, R::AtLeast(0),
            "odometry rotation variance [rad^2] per metre travelled");
  v->Double("distance_var_per_s", &n->distance_var_per_s, R::AtLeast(0),
            "odometry distance variance [m^2] per second (a standing robot stays well-posed)");
  v->Double("rotation_var_per_s", &n->rotation_var_per_s, R::AtLeast(0),
            "odometry rotation variance [rad^2] per second");
}

}  // namespace slammtt
