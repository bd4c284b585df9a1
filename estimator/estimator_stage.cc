#include "estimator/estimator_stage.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "estimator/angle.h"
#include "runtime/log.h"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"

namespace slammtt {
namespace {

double Double(const Config& s, const std::string& key, double fallback) {
  return s.GetDouble(key, fallback);
}

// Reads a key and checks it with the library's own validation afterwards (one place for the
// rules: CheckEstimatorOptions); here only conversions.
double Degrees(const Config& s, const std::string& key, double fallback_rad) {
  return DegreesToRadians(s.GetDouble(key, RadiansToDegrees(fallback_rad)));
}

int IntKey(const Config& s, const std::string& key, int fallback, int min, int max) {
  const int64_t value = s.GetInt(key, fallback);
  if (value < min || value > max) {
    s.FailKey(key, "must be between " + std::to_string(min) + " and " + std::to_string(max));
  }
  return static_cast<int>(value);
}

class TimerObserver : public StepObserver {
 public:
  explicit TimerObserver(StageTimer* timer) : timer_(timer) {}
  void SubstageDone(Substage substage) override { timer_->Lap(SubstageName(substage)); }

 private:
  StageTimer* timer_;
};

int8_t ClassCode(ObjectClass c) {
  switch (c) {
    case ObjectClass::kStatic:
      return slammtt_msgs::track_t::CLASS_STATIC;
    case ObjectClass::kMoving:
      return slammtt_msgs::track_t::CLASS_MOVING;
    case ObjectClass::kUndecided:
      return slammtt_msgs::track_t::CLASS_UNDECIDED;
  }
  return slammtt_msgs::track_t::CLASS_UNDECIDED;
}

FeatureReading PointReading(const slammtt_msgs::feature_t& f) {
  FeatureReading reading;
  reading.range_m = f.range_m;
  reading.bearing_rad = f.bearing_rad;
  reading.range_var_m2 = f.range_var_m2;
  reading.bearing_var_rad2 = f.bearing_var_rad2;
  reading.range_bearing_cov_m_rad = f.range_bearing_cov_m_rad;
  reading.width_m = f.width_m;
  return reading;
}

// Position of a point feature in the sensor frame.
Eigen::Vector2d SensorPoint(const slammtt_msgs::feature_t& f) {
  return f.range_m * Eigen::Vector2d(std::cos(f.bearing_rad), std::sin(f.bearing_rad));
}

}  // namespace

ScanInput ScanInputFromFeatures(const slammtt_msgs::features_t& message, bool person_features) {
  ScanInput scan;
  scan.utime = message.utime;
  const size_t num_points = message.features.size();
  std::vector<bool> is_leg(num_points, false);
  if (person_features) {
    for (const slammtt_msgs::person_feature_t& p : message.people) {
      FeatureReading reading;
      reading.range_m = p.range_m;
      reading.bearing_rad = p.bearing_rad;
      reading.range_var_m2 = p.range_var_m2;
      reading.bearing_var_rad2 = p.bearing_var_rad2;
      reading.range_bearing_cov_m_rad = p.range_bearing_cov_m_rad;
      std::vector<const slammtt_msgs::feature_t*> legs;
      for (int k = 0; k < 2 && k < p.num_legs; ++k) {
        const int32_t index = p.leg_index[k];
        if (index < 0 || static_cast<size_t>(index) >= num_points || is_leg[index]) continue;
        is_leg[static_cast<size_t>(index)] = true;
        legs.push_back(&message.features[static_cast<size_t>(index)]);
      }
      if (legs.size() == 2) {
        reading.width_m = (SensorPoint(*legs[0]) - SensorPoint(*legs[1])).norm() +
                          0.5 * (legs[0]->width_m + legs[1]->width_m);
      } else if (legs.size() == 1) {
        reading.width_m = legs[0]->width_m;
      }
      scan.features.push_back(reading);
    }
  }
  for (size_t k = 0; k < num_points; ++k) {
    if (!is_leg[k]) scan.features.push_back(PointReading(message.features[k]));
  }
  return scan;
}

EstimatorStageOptions ReadEstimatorOptions(const Config& s) {
  EstimatorStageOptions stage;
  EstimatorOptions& o = stage.estimator;
  const std::string mode = s.GetString("mode", AssociationModeName(o.mode));
  if (mode == "ml_ransac") {
    o.mode = AssociationMode::kMlRansac;
  } else if (mode == "static_nn") {
    o.mode = AssociationMode::kStaticNearestNeighbour;
  } else if (mode == "ransac_all_pairs") {
    o.mode = AssociationMode::kRansacAllPairs;
  } else {
    s.FailKey("mode", "expected ml_ransac, static_nn or ransac_all_pairs, got '" + mode + "'");
  }
  stage.person_features = s.GetBool("person_features", stage.person_features);
  const int64_t seed = s.GetInt("seed", 1);
  if (seed < 0) s.FailKey("seed", "must not be negative");
  stage.seed = static_cast<uint64_t>(seed);
  if (s.Has("initial_pose")) {
    const std::vector<double> pose = s.GetDoubles("initial_pose", {});
    if (pose.size() != 3) s.FailKey("initial_pose", "expected [x_m, y_m, heading_deg]");
    o.initial_pose = Eigen::Vector3d(pose[0], pose[1], WrapAngle(DegreesToRadians(pose[2])));
  }
  o.sensor.forward_m = Double(s, "sensor_forward_m", o.sensor.forward_m);
  o.sensor.left_m = Double(s, "sensor_left_m", o.sensor.left_m);
  o.default_range_sigma_m = Double(s, "range_sigma_m", o.default_range_sigma_m);
  o.default_bearing_sigma_rad = Degrees(s, "bearing_sigma_deg", o.default_bearing_sigma_rad);
  o.use_feature_covariance = s.GetBool("use_feature_covariance", o.use_feature_covariance);
  o.min_range_sigma_m = Double(s, "min_range_sigma_m", o.min_range_sigma_m);
  o.min_bearing_sigma_rad = Degrees(s, "min_bearing_sigma_deg", o.min_bearing_sigma_rad);
  o.min_range_m = Double(s, "min_range_m", o.min_range_m);
  o.max_range_m = Double(s, "max_range_m", o.max_range_m);
  o.field_of_view_rad = Degrees(s, "field_of_view_deg", o.field_of_view_rad);
  o.detection_range_m = Double(s, "detection_range_m", o.detection_range_m);
  o.edge_of_view_sigma_m = Double(s, "edge_of_view_sigma_m", o.edge_of_view_sigma_m);
  OdometryNoiseOptions& n = o.odometry_noise;
  n.distance_var_per_m = Double(s, "odometry_distance_var_per_m", n.distance_var_per_m);
  n.rotation_var_per_rad = Double(s, "odometry_rotation_var_per_rad", n.rotation_var_per_rad);
  n.rotation_var_per_m = Double(s, "odometry_rotation_var_per_m", n.rotation_var_per_m);
  n.distance_var_per_s = Double(s, "odometry_distance_var_per_s", n.distance_var_per_s);
  n.rotation_var_per_s = Double(s, "odometry_rotation_var_per_s", n.rotation_var_per_s);
  o.heading_drift_sigma_rad_per_m = Double(s, "odometry_heading_drift_sigma_rad_per_m",
                                           o.heading_drift_sigma_rad_per_m);
  o.heading_drift_walk_var_per_m = Double(s, "odometry_heading_drift_walk_var_per_m",
                                          o.heading_drift_walk_var_per_m);
  o.mover_acceleration_sigma_mps2 =
      Double(s, "moving_acceleration_sigma_mps2", o.mover_acceleration_sigma_mps2);
  o.undecided_acceleration_sigma_mps2 =
      Double(s, "undecided_acceleration_sigma_mps2", o.undecided_acceleration_sigma_mps2);
  o.new_object_velocity_sigma_mps =
      Double(s, "new_object_velocity_sigma_mps", o.new_object_velocity_sigma_mps);
  o.manoeuvre_velocity_sigma_mps =
      Double(s, "manoeuvre_velocity_sigma_mps", o.manoeuvre_velocity_sigma_mps);
  o.max_time_gap_s = Double(s, "max_time_gap_s", o.max_time_gap_s);
  o.max_prediction_s = Double(s, "max_prediction_s", o.max_prediction_s);
  o.time_jump_back_restart_s =
      Double(s, "time_jump_back_restart_s", o.time_jump_back_restart_s);
  o.gap_robot_position_sigma_mps =
      Double(s, "gap_robot_position_sigma_mps", o.gap_robot_position_sigma_mps);
  o.gap_robot_heading_sigma_radps =
      Degrees(s, "gap_robot_heading_sigma_degps", o.gap_robot_heading_sigma_radps);
  o.gap_mover_velocity_sigma_mps =
      Double(s, "gap_velocity_sigma_mps", o.gap_mover_velocity_sigma_mps);
  o.extrapolation_speed_sigma_mps =
      Double(s, "extrapolation_speed_sigma_mps", o.extrapolation_speed_sigma_mps);
  o.extrapolation_turn_sigma_radps =
      Degrees(s, "extrapolation_turn_sigma_degps", o.extrapolation_turn_sigma_radps);
  o.max_objects = IntKey(s, "max_objects", o.max_objects, 0, 100000);
  o.gate_d1_chi2 = Double(s, "gate_d1", o.gate_d1_chi2);
  o.level3 = s.GetBool("level3", o.level3);
  o.gate_d2_chi2 = Double(s, "gate_d2", o.gate_d2_chi2);
  o.new_object_gate_dn_chi2 = Double(s, "gate_dn", o.new_object_gate_dn_chi2);
  o.ransac.success_probability = Double(s, "ransac_probability", o.ransac.success_probability);
  o.ransac.max_hypotheses = IntKey(s, "max_hypotheses", o.ransac.max_hypotheses, 1, 1000000);
  o.ransac.inlier_chi2 = Double(s, "ransac_inlier_chi2", o.ransac.inlier_chi2);
  o.update_group_size = IntKey(s, "update_group_size", o.update_group_size, 1, 4096);
  o.max_static_updates_per_scan = IntKey(s, "max_static_updates_per_scan",
                                         o.max_static_updates_per_scan, 0, 100000);
  o.tracks.confirm_hits = IntKey(s, "confirm_hits", o.tracks.confirm_hits, 1, 1000);
  o.tracks.prune_unseen_s = Double(s, "prune_unseen_s", o.tracks.prune_unseen_s);
  o.tracks.tentative_prune_unseen_s =
      Double(s, "tentative_prune_unseen_s", o.tracks.tentative_prune_unseen_s);
  o.tracks.static_prune_unseen_in_view_s =
      Double(s, "static_prune_unseen_in_view_s", o.tracks.static_prune_unseen_in_view_s);
  o.tracks.prune_unseen_visible_s =
      Double(s, "prune_unseen_visible_s", o.tracks.prune_unseen_visible_s);
  o.tracks.shadow_radius_m = Double(s, "shadow_radius_m", o.tracks.shadow_radius_m);
  o.tracks.coast_confirmed_s = Double(s, "coast_confirmed_s", o.tracks.coast_confirmed_s);
  o.tracks.coast_unseen_s = Double(s, "coast_unseen_s", o.tracks.coast_unseen_s);
  o.tracks.prune_out_of_view_s = Double(s, "prune_out_of_view_s", o.tracks.prune_out_of_view_s);
  o.tracks.max_coast_sigma_m = Double(s, "max_coast_sigma_m", o.tracks.max_coast_sigma_m);
  o.tracks.reacquire_speed_mps =
      Double(s, "reacquire_speed_mps", o.tracks.reacquire_speed_mps);
  MotionClassifierOptions& c = o.classifier;
  c.moving_chi2 = Double(s, "moving_chi2", c.moving_chi2);
  c.moving_min_speed_mps = Double(s, "moving_min_speed_mps", c.moving_min_speed_mps);
  c.moving_confirm_scans = IntKey(s, "moving_confirm_scans", c.moving_confirm_scans, 1, 1000);
  c.still_max_speed_mps = Double(s, "still_max_speed_mps", c.still_max_speed_mps);
  c.still_velocity_chi2 = Double(s, "still_velocity_chi2", c.still_velocity_chi2);
  c.still_restart_variance_ratio =
      Double(s, "still_restart_variance_ratio", c.still_restart_variance_ratio);
  c.still_hold_s = Double(s, "still_hold_s", c.still_hold_s);
  c.started_moving_chi2 = Double(s, "started_moving_chi2", c.started_moving_chi2);
  s.CheckUnused();
  const std::string problem = CheckEstimatorOptions(o);
  if (!problem.empty()) s.Fail(problem);
  return stage;
}

EstimatorStage::EstimatorStage(const EstimatorStageOptions& options, const Channels& channels)
    : estimator_(options.estimator),
      rng_(options.seed),
      person_features_(options.person_features),
      odometry_channel_(channels.Get("odometry")),
      features_channel_(channels.Get("features")),
      pose_channel_(channels.Get("pose")),
      map_channel_(channels.Get("map")),
      tracks_channel_(channels.Get("tracks")),
      status_channel_(channels.Get("estimator_status")),
      timing_channel_(channels.Get("stage_timing")) {}

EstimatorStage::EstimatorStage(const ProcessSettings& settings)
    : EstimatorStage(ReadEstimatorOptions(settings.config.Child("estimator")), settings.channels) {}

std::vector<std::string> EstimatorStage::InputChannels() const {
  return {odometry_channel_, features_channel_};
}

void EstimatorStage::Handle(const std::string& channel, const void* data, int size,
                            MessageSink& out) {
  if (channel == odometry_channel_) {
    HandleOdometry(data, size, out);
  } else if (channel == features_channel_) {
    HandleFeatures(data, size, out);
  }
}

void EstimatorStage::Undecodable(const std::string& what) {
  const int64_t n = ++counters_.messages_undecodable;
  // The 1st, 10th, 100th, ... occurrence: visible without flooding the log.
  if (IsReportable(n)) LogWarning() << "estimator: " << what << " (" << n << " so far)";
}

void EstimatorStage::HandleOdometry(const void* data, int size, MessageSink& out) {
  slammtt_msgs::odometry_t message;
  if (!Decode(data, size, &message)) {
    Undecodable("undecodable odometry_t message dropped");
    return;
  }
  OdometryReading reading;
  reading.utime = message.utime;
  reading.pose = Eigen::Vector3d(message.x_m, message.y_m, message.heading_rad);
  reading.linear_mps = message.linear_velocity_mps;
  reading.angular_radps = message.angular_velocity_radps;
  if (!estimator_.AddOdometry(reading)) PublishStatus(message.utime, out);
}

void EstimatorStage::HandleFeatures(const void* data, int size, MessageSink& out) {
  slammtt_msgs::features_t message;
  if (!Decode(data, size, &message)) {
    Undecodable("undecodable features_t message dropped");
    return;
  }
  StageTimer timer("estimator", message.utime);
  const ScanInput scan = ScanInputFromFeatures(message, person_features_);
  TimerObserver observer(&timer);
  const ScanResult result = estimator_.ProcessScan(scan, &rng_, &observer);
  if (!result.processed) {
    PublishStatus(message.utime, out);
    return;
  }
  timer.Count("features", result.counts.features);
  timer.Count("objects", static_cast<int64_t>(result.objects.size()));
  timer.Count("hypotheses", result.counts.hypotheses);
  timer.Count("updates", result.counts.level1_updates + result.counts.level2_updates +
                             result.counts.level3_updates);
  timer.Count("updates_skipped", result.counts.static_updates_skipped);
  timer.Count("lines_unused", message.num_lines);
  const slammtt_msgs::stage_timing_t timing = timer.Finish();

  slammtt_msgs::pose_t pose;
  pose.utime = message.utime;
  pose.x_m = result.pose(0);
  pose.y_m = result.pose(1);
  pose.heading_rad = result.pose(2);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) pose.covariance[3 * r + c] = result.pose_covariance(r, c);
  }
  slammtt_msgs::map_t map;
  map.utime = message.utime;
  slammtt_msgs::tracks_t tracks;
  tracks.utime = message.utime;
  for (const ObjectEstimate& e : result.objects) {
    slammtt_msgs::track_t track;
    track.id = e.id;
    track.x_m = e.position(0);
    track.y_m = e.position(1);
    track.vx_mps = e.velocity(0);
    track.vy_mps = e.velocity(1);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) track.covariance[4 * r + c] = e.covariance(r, c);
    }
    track.object_class = ClassCode(e.object_class);
    track.confirmed = e.confirmed;
    track.first_seen_utime = e.first_seen_utime;
    track.hits = e.hits;
    track.last_seen_utime = e.last_seen_utime;
    tracks.tracks.push_back(track);
    if (e.object_class == ObjectClass::kStatic && e.confirmed) {
      slammtt_msgs::landmark_t landmark;
      landmark.id = e.id;
      landmark.x_m = e.position(0);
      landmark.y_m = e.position(1);
      landmark.covariance[0] = e.covariance(0, 0);
      landmark.covariance[1] = e.covariance(0, 1);
      landmark.covariance[2] = e.covariance(1, 0);
      landmark.covariance[3] = e.covariance(1, 1);
      map.landmarks.push_back(landmark);
    }
  }
  tracks.num_tracks = static_cast<int32_t>(tracks.tracks.size());
  map.num_landmarks = static_cast<int32_t>(map.landmarks.size());
  out.PublishMessage(pose_channel_, pose);
  out.PublishMessage(map_channel_, map);
  out.PublishMessage(tracks_channel_, tracks);
  PublishStatus(message.utime, out);
  out.PublishMessage(timing_channel_, timing);
  ++counters_.scans_published;
}

void EstimatorStage::PublishStatus(int64_t utime, MessageSink& out) {
  const EstimatorCounters& c = estimator_.counters();
  slammtt_msgs::estimator_status_t status;
  status.utime = utime;
  status.scans_processed = c.scans_processed;
  status.odometry_processed = c.odometry_processed;
  status.features_rejected = c.features_rejected;
  status.messages_out_of_order = c.messages_out_of_order;
  status.time_gaps = c.time_gaps;
  status.scans_without_odometry = c.scans_without_odometry;
  status.object_cap_hits = c.object_cap_hits;
  status.hypotheses_generated = c.hypotheses_generated;
  status.num_landmarks = estimator_.NumObjectsOfClass(ObjectClass::kStatic, false);
  status.num_moving = estimator_.NumObjectsOfClass(ObjectClass::kMoving, false);
  status.num_tentative = estimator_.NumTentative();
  status.last_event = estimator_.last_event();
  status.odometry_rejected = c.odometry_rejected;
  status.messages_undecodable = counters_.messages_undecodable;
  status.updates_failed = c.updates_failed;
  status.restarts = c.restarts;
  const SlamState& state = estimator_.state();
  status.heading_drift_rad_per_m = state.heading_drift_rad_per_m();
  status.heading_drift_sigma_rad_per_m = std::sqrt(std::max(0.0, state.heading_drift_variance()));
  out.PublishMessage(status_channel_, status);
}

std::unique_ptr<Stage> CreateEstimatorStage(const ProcessSettings& settings) {
  return std::make_unique<EstimatorStage>(settings);
}

}  // namespace slammtt
