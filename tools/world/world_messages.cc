#include "tools/world/world_messages.h"

#include <algorithm>
#include <cmath>

#include "runtime/lcm_io.h"

namespace slammtt {

namespace {

int8_t KindConstant(ObjectKind kind) {
  using slammtt_msgs::object_truth_t;
  switch (kind) {
    case ObjectKind::kWall:
      return object_truth_t::KIND_WALL;
    case ObjectKind::kFurniture:
      return object_truth_t::KIND_FURNITURE;
    case ObjectKind::kPost:
      return object_truth_t::KIND_POST;
    case ObjectKind::kDisc:
      return object_truth_t::KIND_DISC;
    case ObjectKind::kPerson:
      return object_truth_t::KIND_PERSON;
    case ObjectKind::kLeg:
      return object_truth_t::KIND_LEG;
  }
  return object_truth_t::KIND_POST;
}

}  // namespace

slammtt_msgs::odometry_t ToOdometryMessage(const OdometryReading& reading, int64_t utime_offset) {
  slammtt_msgs::odometry_t msg{};
  msg.utime = utime_offset + reading.time_us;
  msg.sequence = reading.sequence;
  msg.x_m = reading.pose.x_m;
  msg.y_m = reading.pose.y_m;
  msg.heading_rad = reading.pose.heading_rad;
  msg.linear_velocity_mps = reading.linear_mps;
  msg.angular_velocity_radps = reading.angular_radps;
  msg.left_wheel_velocity_mps = reading.left_wheel_mps;
  msg.right_wheel_velocity_mps = reading.right_wheel_mps;
  return msg;
}

slammtt_msgs::ground_truth_t ToGroundTruthMessage(const TruthSnapshot& truth,
                                                  int64_t utime_offset) {
  slammtt_msgs::ground_truth_t msg{};
  msg.utime = utime_offset + truth.time_us;
  msg.robot_x_m = truth.robot.pose.x_m;
  msg.robot_y_m = truth.robot.pose.y_m;
  msg.robot_heading_rad = truth.robot.pose.heading_rad;
  msg.robot_linear_mps = truth.robot.linear_mps;
  msg.robot_angular_radps = truth.robot.angular_radps;
  msg.num_objects = static_cast<int32_t>(truth.objects.size());
  msg.objects.reserve(truth.objects.size());
  for (const ObjectTruth& o : truth.objects) {
    slammtt_msgs::object_truth_t object{};
    object.id = o.id;
    object.x_m = o.x_m;
    object.y_m = o.y_m;
    object.vx_mps = o.vx_mps;
    object.vy_mps = o.vy_mps;
    object.radius_m = o.radius_m;
    object.object_class = o.is_static ? slammtt_msgs::object_truth_t::CLASS_STATIC
                                      : slammtt_msgs::object_truth_t::CLASS_MOVING;
    object.beams_on_object = o.beams_on_object;
    object.visible = o.visible;
    object.kind = KindConstant(o.kind);
    object.parent_id = o.parent_id;
    msg.objects.push_back(object);
  }
  msg.num_segments = static_cast<int32_t>(truth.segments.size());
  msg.segments.reserve(truth.segments.size());
  for (const SegmentTruth& s : truth.segments) {
    slammtt_msgs::segment_truth_t segment{};
    segment.id = s.id;
    segment.kind = KindConstant(s.kind);
    segment.x0_m = s.segment.x0_m;
    segment.y0_m = s.segment.y0_m;
    segment.x1_m = s.segment.x1_m;
    segment.y1_m = s.segment.y1_m;
    segment.beams_on_segment = s.beams_on_segment;
    msg.segments.push_back(segment);
  }
  return msg;
}

slammtt_msgs::laser_scan_t ToLaserScanMessage(const SensorFrame& frame, const LaserSpec& laser,
                                              int64_t utime_offset) {
  slammtt_msgs::laser_scan_t msg{};
  msg.utime = utime_offset + frame.time_us;
  msg.sequence = frame.sequence;
  msg.scan_duration_us = 0;
  msg.range_min_m = static_cast<float>(laser.min_range_m);
  msg.range_max_m = static_cast<float>(laser.max_range_m);
  msg.num_beams = static_cast<int32_t>(frame.scan.size());
  msg.angle_rad.reserve(frame.scan.size());
  msg.range_m.reserve(frame.scan.size());
  msg.intensity.reserve(frame.scan.size());
  msg.valid.reserve(frame.scan.size());
  for (const SimulatedBeam& beam : frame.scan) {
    msg.angle_rad.push_back(static_cast<float>(beam.angle_rad));
    msg.range_m.push_back(beam.valid ? static_cast<float>(beam.range_m) : 0.0f);
    msg.intensity.push_back(beam.valid ? 1.0f : 0.0f);
    msg.valid.push_back(beam.valid);
  }
  return msg;
}

slammtt_msgs::features_t ToFeaturesMessage(const SensorFrame& frame, int64_t utime_offset) {
  slammtt_msgs::features_t msg{};
  msg.utime = utime_offset + frame.time_us;
  msg.sequence = frame.sequence;
  msg.num_features = static_cast<int32_t>(frame.features.size());
  msg.features.reserve(frame.features.size());
  for (const PointFeature& f : frame.features) {
    slammtt_msgs::feature_t feature{};
    feature.range_m = f.range_m;
    feature.bearing_rad = f.bearing_rad;
    feature.width_m = f.width_m;
    feature.num_points = 0;
    feature.range_var_m2 = f.range_var_m2;
    feature.bearing_var_rad2 = f.bearing_var_rad2;
    feature.range_bearing_cov_m_rad = 0.0;
    msg.features.push_back(feature);
  }
  return msg;
}

slammtt_msgs::laser_geometry_t ToLaserGeometryMessage(const Scenario& scenario, int64_t utime) {
  const LaserSpec& laser = scenario.laser;
  slammtt_msgs::laser_geometry_t msg{};
  msg.utime = utime;
  msg.mount_forward_m = laser.mount_a_m;
  msg.mount_left_m = laser.mount_b_m;
  // Degrees to radians as every configuration reader converts them (common/options_schema.h),
  // so that an estimator taking these values estimates bit for bit as with its configuration.
  msg.mount_yaw_rad = laser.mount_yaw_deg * M_PI / 180.0;
  const double fov_rad = laser.fov_deg * M_PI / 180.0;
  msg.view_start_rad = -0.5 * fov_rad;
  msg.view_end_rad = 0.5 * fov_rad;
  msg.range_min_m = laser.min_range_m;
  msg.range_max_m = laser.max_range_m;
  msg.source = "slammtt-world, scenario " + scenario.name;
  return msg;
}

bool FrameCarriesGeometry(const LaserSpec& laser, int64_t sequence) {
  const int64_t period = std::max<int64_t>(1, std::llround(laser.rate_hz));
  return sequence % period == 0;
}

std::vector<EncodedMessage> EncodeWorldEvent(const WorldEvent& event, const Scenario& scenario,
                                             const WorldChannels& channels, int64_t utime_offset) {
  const LaserSpec& laser = scenario.laser;
  std::vector<EncodedMessage> out;
  const int64_t utime = utime_offset + event.time_us;
  if (event.kind == WorldEvent::Kind::kOdometry) {
    out.push_back(
        {utime, channels.odometry, Encode(ToOdometryMessage(event.odometry, utime_offset))});
    return out;
  }
  const SensorFrame& frame = event.sensor;
  if (FrameCarriesGeometry(laser, frame.sequence)) {
    out.push_back({utime, channels.laser_geometry, Encode(ToLaserGeometryMessage(scenario, utime))});
  }
  out.push_back(
      {utime, channels.ground_truth, Encode(ToGroundTruthMessage(frame.truth, utime_offset))});
  if (frame.has_scan) {
    out.push_back(
        {utime, channels.laser_scan, Encode(ToLaserScanMessage(frame, laser, utime_offset))});
  }
  if (frame.has_features) {
    out.push_back({utime, channels.features, Encode(ToFeaturesMessage(frame, utime_offset))});
  }
  return out;
}

}  // namespace slammtt
