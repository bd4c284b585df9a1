#include "estimator/smoother_input_message.h"

#include "estimator/row_major.h"

namespace slammtt {

slammtt_msgs::smoother_input_t SmootherInputMessage(const SmootherScanInput& input) {
  slammtt_msgs::smoother_input_t message;
  message.utime = input.utime;
  message.x_m = input.pose(0);
  message.y_m = input.pose(1);
  message.heading_rad = input.pose(2);
  WriteRowMajor<3>(input.pose_covariance, message.pose_covariance);
  message.continues = input.continues;
  message.dx_m = input.increment(0);
  message.dy_m = input.increment(1);
  message.dtheta_rad = input.increment(2);
  WriteRowMajor<3>(input.increment_covariance, message.increment_covariance);
  message.sensor_forward_m = input.mount.forward_m;
  message.sensor_left_m = input.mount.left_m;
  message.sensor_yaw_rad = input.mount.yaw_rad;
  message.observations.reserve(input.observations.size());
  for (const StaticObservation& o : input.observations) {
    slammtt_msgs::smoother_observation_t observation;
    observation.landmark_id = o.landmark_id;
    observation.range_m = o.range_bearing(0);
    observation.bearing_rad = o.range_bearing(1);
    WriteRowMajor<2>(o.covariance, observation.covariance);
    observation.tentative = o.tentative;
    message.observations.push_back(observation);
  }
  message.num_observations = static_cast<int32_t>(message.observations.size());
  message.removed_landmark_ids = input.removed_landmark_ids;
  message.num_removed = static_cast<int32_t>(message.removed_landmark_ids.size());
  return message;
}

SmootherScanInput SmootherScanInputFromMessage(const slammtt_msgs::smoother_input_t& message) {
  SmootherScanInput input;
  input.utime = message.utime;
  input.pose = Eigen::Vector3d(message.x_m, message.y_m, message.heading_rad);
  input.pose_covariance = ReadRowMajor<3>(message.pose_covariance);
  input.continues = message.continues;
  input.increment = Eigen::Vector3d(message.dx_m, message.dy_m, message.dtheta_rad);
  input.increment_covariance = ReadRowMajor<3>(message.increment_covariance);
  input.mount.forward_m = message.sensor_forward_m;
  input.mount.left_m = message.sensor_left_m;
  input.mount.yaw_rad = message.sensor_yaw_rad;
  input.observations.reserve(message.observations.size());
  for (const slammtt_msgs::smoother_observation_t& o : message.observations) {
    input.observations.push_back(StaticObservation{
        o.landmark_id, Eigen::Vector2d(o.range_m, o.bearing_rad), ReadRowMajor<2>(o.covariance),
        o.tentative != 0});
  }
  input.removed_landmark_ids = message.removed_landmark_ids;
  return input;
}

}  // namespace slammtt
