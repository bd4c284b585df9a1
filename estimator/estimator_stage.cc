#include "estimator/estimator_stage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

#include "estimator/row_major.h"
#include "estimator/smoother_input_message.h"
#include "runtime/config_options.h"
#include "runtime/log.h"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/pose_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "slammtt_msgs/tracks_t.hpp"

namespace slammtt {
namespace {

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

// Text from a message, fit for one log line: control characters become '?', and at most 200
// bytes are kept.
std::string OneLine(const std::string& text) {
  std::string line = text.substr(0, 200);
  for (char& c : line) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  }
  return line;
}

// The counters of stage_timing_t for one processed scan.
void CountScanWork(const ScanResult& result, StageTimer* timer) {
  const StepCounts& counts = result.counts;
  timer->Count("features", counts.features);
  timer->Count("objects", static_cast<int64_t>(result.objects.size()));
  timer->Count("hypotheses", counts.hypotheses);
  timer->Count("updates", counts.level1_updates + counts.level2_updates + counts.level3_updates);
  timer->Count("updates_skipped", counts.static_updates_skipped);
  timer->Count("lines", counts.lines);
  timer->Count("line_updates", counts.line_updates);
  timer->Count("new_lines", counts.new_lines);
  timer->Count("features_over_cap", counts.features_over_cap);
  timer->Count("ransac_pair_tests", counts.ransac_pair_tests);
  timer->Count("ransac_budget_cut", counts.ransac_budget_cut);
  timer->Count("state_recovered", counts.state_recovered);
  timer->Count("archived", static_cast<int64_t>(result.archived_landmarks.size()));
}

slammtt_msgs::pose_t PoseMessage(int64_t utime, const ScanResult& result) {
  slammtt_msgs::pose_t pose;
  pose.utime = utime;
  pose.x_m = result.pose(0);
  pose.y_m = result.pose(1);
  pose.heading_rad = result.pose(2);
  WriteRowMajor<3>(result.pose_covariance, pose.covariance);
  return pose;
}

slammtt_msgs::track_t TrackMessage(const ObjectEstimate& e) {
  slammtt_msgs::track_t track;
  track.id = e.id;
  track.x_m = e.position(0);
  track.y_m = e.position(1);
  track.vx_mps = e.velocity(0);
  track.vy_mps = e.velocity(1);
  WriteRowMajor<4>(e.covariance, track.covariance);
  track.object_class = ClassCode(e.object_class);
  track.confirmed = e.confirmed;
  track.first_seen_utime = e.first_seen_utime;
  track.hits = e.hits;
  track.last_seen_utime = e.last_seen_utime;
  track.measured = e.measured;
  track.coasting_s = e.coasting_s;
  track.reported = e.reported;
  track.kind = e.kind == ObjectKind::kPerson ? slammtt_msgs::track_t::KIND_PERSON
                                             : slammtt_msgs::track_t::KIND_OTHER;
  return track;
}

// Every object, in the estimator's order.
slammtt_msgs::tracks_t TracksMessage(int64_t utime, const ScanResult& result) {
  slammtt_msgs::tracks_t tracks;
  tracks.utime = utime;
  for (const ObjectEstimate& e : result.objects) tracks.tracks.push_back(TrackMessage(e));
  tracks.num_tracks = static_cast<int32_t>(tracks.tracks.size());
  return tracks;
}

slammtt_msgs::line_landmark_t LineLandmarkMessage(const LineEstimate& e) {
  slammtt_msgs::line_landmark_t line;
  line.id = e.id;
  line.rho_m = e.line(0);
  line.alpha_rad = e.line(1);
  WriteRowMajor<2>(e.covariance, line.covariance);
  line.from_x_m = e.from_m(0);
  line.from_y_m = e.from_m(1);
  line.to_x_m = e.to_m(0);
  line.to_y_m = e.to_m(1);
  line.hits = e.hits;
  return line;
}

// The confirmed static objects that are not people (the state's, then the local window's
// archive's: landmark_window.h), and every line landmark.
slammtt_msgs::map_t MapMessage(int64_t utime, const ScanResult& result) {
  slammtt_msgs::map_t map;
  map.utime = utime;
  std::vector<const ObjectEstimate*> objects;
  for (const ObjectEstimate& e : result.objects) objects.push_back(&e);
  for (const ObjectEstimate& e : result.archived_landmarks) objects.push_back(&e);
  for (const ObjectEstimate* object : objects) {
    const ObjectEstimate& e = *object;
    // A standing person is a STATIC object of kind PERSON: tracked, never part of the map.
    if (e.object_class != ObjectClass::kStatic || !e.confirmed || e.kind == ObjectKind::kPerson) {
      continue;
    }
    slammtt_msgs::landmark_t landmark;
    landmark.id = e.id;
    landmark.x_m = e.position(0);
    landmark.y_m = e.position(1);
    WriteRowMajor<2>(e.covariance.topLeftCorner<2, 2>(), landmark.covariance);
    map.landmarks.push_back(landmark);
  }
  for (const LineEstimate& e : result.lines) map.lines.push_back(LineLandmarkMessage(e));
  map.num_landmarks = static_cast<int32_t>(map.landmarks.size());
  map.num_lines = static_cast<int32_t>(map.lines.size());
  return map;
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
      reading.person = true;
      std::vector<const slammtt_msgs::feature_t*> legs;
      for (int k = 0; k < 2 && k < p.num_legs; ++k) {
        const int32_t index = p.leg_index[k];
        if (index < 0 || static_cast<size_t>(index) >= num_points || is_leg[index]) continue;
        is_leg[static_cast<size_t>(index)] = true;
        legs.push_back(&message.features[static_cast<size_t>(index)]);
      }
      if (legs.size() == 2) {
        reading.pair_confidence = p.confidence;
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
  scan.lines.reserve(message.lines.size());
  for (const slammtt_msgs::line_feature_t& l : message.lines) {
    LineReading reading;
    reading.rho_m = l.rho_m;
    reading.alpha_rad = l.alpha_rad;
    reading.rho_var_m2 = l.rho_var_m2;
    reading.alpha_var_rad2 = l.alpha_var_rad2;
    reading.rho_alpha_cov_m_rad = l.rho_alpha_cov_m_rad;
    reading.first_m = Eigen::Vector2d(l.first_x_m, l.first_y_m);
    reading.last_m = Eigen::Vector2d(l.last_x_m, l.last_y_m);
    scan.lines.push_back(reading);
  }
  return scan;
}

const std::vector<RenamedKey>& RenamedEstimatorKeys() {
  static const std::vector<RenamedKey> renamed = {
      {"range_sigma_m", "default_range_sigma_m"},
      {"bearing_sigma_deg", "default_bearing_sigma_deg"},
      {"odometry_distance_var_per_m", "odometry_noise_distance_var_per_m"},
      {"odometry_rotation_var_per_rad", "odometry_noise_rotation_var_per_rad"},
      {"odometry_rotation_var_per_m", "odometry_noise_rotation_var_per_m"},
      {"odometry_distance_var_per_s", "odometry_noise_distance_var_per_s"},
      {"odometry_rotation_var_per_s", "odometry_noise_rotation_var_per_s"},
      {"odometry_heading_drift_sigma_rad_per_m", "heading_drift_sigma_rad_per_m"},
      {"odometry_heading_drift_walk_var_per_m", "heading_drift_walk_var_per_m"},
      {"moving_acceleration_sigma_mps2", "mover_acceleration_sigma_mps2"},
      {"gap_velocity_sigma_mps", "gap_mover_velocity_sigma_mps"},
      {"gate_d1", "gate_d1_chi2"},
      {"gate_d2", "gate_d2_chi2"},
      {"gate_dn", "new_object_gate_dn_chi2"},
      {"ransac_probability", "ransac_success_probability"},
      {"max_hypotheses", "ransac_max_hypotheses"},
      {"confirm_hits", "tracks_confirm_hits"},
      {"prune_unseen_s", "tracks_prune_unseen_s"},
      {"tentative_prune_unseen_s", "tracks_tentative_prune_unseen_s"},
      {"static_prune_unseen_in_view_s", "tracks_static_prune_unseen_in_view_s"},
      {"prune_unseen_visible_s", "tracks_prune_unseen_visible_s"},
      {"shadow_radius_m", "tracks_shadow_radius_m"},
      {"coast_confirmed_s", "tracks_coast_confirmed_s"},
      {"coast_unseen_s", "tracks_coast_unseen_s"},
      {"prune_out_of_view_s", "tracks_prune_out_of_view_s"},
      {"max_coast_sigma_m", "tracks_max_coast_sigma_m"},
      {"reacquire_speed_mps", "tracks_reacquire_speed_mps"},
      {"moving_chi2", "classifier_moving_chi2"},
      {"moving_min_speed_mps", "classifier_moving_min_speed_mps"},
      {"moving_confirm_scans", "classifier_moving_confirm_scans"},
      {"still_max_speed_mps", "classifier_still_max_speed_mps"},
      {"still_velocity_chi2", "classifier_still_velocity_chi2"},
      {"still_restart_variance_ratio", "classifier_still_restart_variance_ratio"},
      {"still_hold_s", "classifier_still_hold_s"},
      {"started_moving_chi2", "classifier_started_moving_chi2"},
  };
  return renamed;
}

void VisitEstimatorStageOptions(OptionVisitor* v, EstimatorStageOptions* o) {
  int64_t seed = static_cast<int64_t>(o->seed);
  v->Int("seed", &seed, OptionRange::AtLeast(0), "seeds the RANSAC generator");
  o->seed = static_cast<uint64_t>(seed);
  v->Bool("person_features", &o->person_features,
          "a person feature is one measurement in place of its legs");
  VisitEstimatorOptions(v, &o->estimator);
}

EstimatorStageOptions ReadEstimatorOptions(const Config& s) {
  RejectRenamedKeys(s, RenamedEstimatorKeys(), "docs/estimator.md, \"Migration\"");
  EstimatorStageOptions stage;
  stage.geometry_given.mount =
      s.Has("sensor_forward_m") || s.Has("sensor_left_m") || s.Has("sensor_yaw_deg");
  stage.geometry_given.field_of_view = s.Has("field_of_view_deg") ||
                                       s.Has("field_of_view_start_deg") ||
                                       s.Has("field_of_view_end_deg");
  stage.geometry_given.max_range = s.Has("max_range_m");
  ConfigOptionReader reader(s);
  VisitEstimatorStageOptions(&reader, &stage);
  s.CheckUnused();
  const std::string problem = CheckEstimatorOptions(stage.estimator);
  if (!problem.empty()) s.Fail(problem);
  return stage;
}

std::string EstimatorStageOptionsTable() {
  EstimatorStageOptions defaults;
  OptionsMarkdownTable table;
  VisitEstimatorStageOptions(&table, &defaults);
  return table.Table();
}

EstimatorStage::EstimatorStage(const EstimatorStageOptions& options, const Channels& channels)
    : estimator_(options.estimator),
      rng_(options.seed),
      person_features_(options.person_features),
      configured_(options.estimator),
      geometry_given_(options.geometry_given),
      odometry_channel_(channels.Get("odometry")),
      features_channel_(channels.Get("features")),
      laser_geometry_channel_(channels.Get("laser_geometry")),
      pose_channel_(channels.Get("pose")),
      map_channel_(channels.Get("map")),
      tracks_channel_(channels.Get("tracks")),
      smoother_input_channel_(channels.Get("smoother_input")),
      smoother_feedback_(options.estimator.smoother_feedback),
      smoothed_pose_channel_(channels.Get("smoothed_pose")),
      smoothed_map_channel_(channels.Get("smoothed_map")),
      status_channel_(channels.Get("estimator_status")),
      timing_channel_(channels.Get("stage_timing")) {}

EstimatorStage::EstimatorStage(const ProcessSettings& settings)
    : EstimatorStage(ReadEstimatorOptions(settings.config.Child("estimator")), settings.channels) {}

std::vector<std::string> EstimatorStage::InputChannels() const {
  if (smoother_feedback_) {
    return {odometry_channel_, features_channel_, laser_geometry_channel_, smoothed_pose_channel_,
            smoothed_map_channel_};
  }
  return {odometry_channel_, features_channel_, laser_geometry_channel_};
}

std::vector<std::string> EstimatorStage::OutputChannels() const {
  return {pose_channel_, map_channel_, tracks_channel_, smoother_input_channel_, status_channel_};
}

void EstimatorStage::Handle(const std::string& channel, const void* data, int size,
                            MessageSink& out) {
  if (channel == odometry_channel_) {
    HandleOdometry(data, size, out);
  } else if (channel == features_channel_) {
    HandleFeatures(data, size, out);
  } else if (channel == laser_geometry_channel_) {
    HandleLaserGeometry(data, size);
  } else if (smoother_feedback_ && channel == smoothed_pose_channel_) {
    HandleSmoothedPose(data, size);
  } else if (smoother_feedback_ && channel == smoothed_map_channel_) {
    HandleSmoothedMap(data, size);
  }
}

void EstimatorStage::HandleSmoothedPose(const void* data, int size) {
  slammtt_msgs::pose_t message;
  if (!Decode(data, size, &message)) {
    Undecodable("undecodable pose_t message on " + smoothed_pose_channel_ + " dropped");
    return;
  }
  const Eigen::Vector3d pose(message.x_m, message.y_m, message.heading_rad);
  if (!pose.allFinite()) return;
  smoothed_pose_ = std::make_pair(message.utime, pose);
}

void EstimatorStage::HandleSmoothedMap(const void* data, int size) {
  slammtt_msgs::map_t message;
  if (!Decode(data, size, &message)) {
    Undecodable("undecodable map_t message on " + smoothed_map_channel_ + " dropped");
    return;
  }
  // The smoother publishes the pose of a scan before its map: without the pose of the same
  // scan, the map alone would move the landmarks away from the robot that sees them.
  if (!smoothed_pose_ || smoothed_pose_->first != message.utime) return;
  SmoothedEstimate smoothed;
  smoothed.utime = message.utime;
  smoothed.pose = smoothed_pose_->second;
  smoothed.landmarks.reserve(message.landmarks.size());
  for (const slammtt_msgs::landmark_t& l : message.landmarks) {
    const Eigen::Vector2d position(l.x_m, l.y_m);
    if (position.allFinite()) smoothed.landmarks.emplace_back(l.id, position);
  }
  estimator_.ApplySmoothedEstimate(smoothed);
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

void EstimatorStage::HandleLaserGeometry(const void* data, int size) {
  slammtt_msgs::laser_geometry_t message;
  if (!Decode(data, size, &message)) {
    Undecodable("undecodable laser_geometry_t message dropped");
    return;
  }
  ++counters_.geometry_messages;
  LaserGeometry log;
  log.mount.forward_m = message.mount_forward_m;
  log.mount.left_m = message.mount_left_m;
  log.mount.yaw_rad = message.mount_yaw_rad;
  log.view.start_rad = message.view_start_rad;
  log.view.end_rad = message.view_end_rad;
  log.view.symmetric = message.view_start_rad == -message.view_end_rad;
  log.max_range_m = message.range_max_m;
  // Publishers repeat their geometry about once a second: only a new one is reconciled and
  // reported. Compared bit for bit, so that a repeated NaN is the same geometry too.
  const std::array<double, 6> values = {log.mount.forward_m, log.mount.left_m,
                                        log.mount.yaw_rad,   log.view.start_rad,
                                        log.view.end_rad,    log.max_range_m};
  if (log_geometry_ &&
      std::memcmp(log_geometry_->data(), values.data(), sizeof(double) * values.size()) == 0) {
    return;
  }
  log_geometry_ = values;
  const std::string source = message.source.empty() ? "" : " (" + OneLine(message.source) + ")";
  const GeometryReconciliation r = ReconcileLaserGeometry(configured_, geometry_given_, log);
  if (!r.problem.empty()) {
    ++counters_.geometry_rejected;
    LogWarning() << "estimator: laser geometry of " << laser_geometry_channel_ << source
                 << " not used: " << r.problem;
    return;
  }
  if (!r.disagreement.empty()) {
    ++counters_.geometry_disagreements;
    LogWarning() << "estimator: the configuration's laser geometry disagrees with "
                 << laser_geometry_channel_ << source << ": " << r.disagreement
                 << "; the configuration's is used";
  }
  if (!r.taken.empty()) {
    LogInfo() << "estimator: laser geometry the configuration does not give, taken from "
              << laser_geometry_channel_ << source << ": " << r.taken;
  }
  estimator_.SetLaserGeometry(r.options);
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
  CountScanWork(result, &timer);
  const slammtt_msgs::stage_timing_t timing = timer.Finish();
  out.PublishMessage(pose_channel_, PoseMessage(message.utime, result));
  out.PublishMessage(map_channel_, MapMessage(message.utime, result));
  out.PublishMessage(tracks_channel_, TracksMessage(message.utime, result));
  PublishSmootherInput(result, out);
  PublishStatus(message.utime, out);
  out.PublishMessage(timing_channel_, timing);
  ++counters_.scans_published;
}

void EstimatorStage::PublishSmootherInput(const ScanResult& result, MessageSink& out) {
  const SmootherScanInput input = smoother_input_.Build(result, estimator_.options().sensor);
  out.PublishMessage(smoother_input_channel_, SmootherInputMessage(input));
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
  status.time_jumps_rejected = c.time_jumps_rejected;
  status.odometry_frame_jumps = c.odometry_frame_jumps;
  status.state_recoveries = c.state_recoveries;
  status.features_over_cap = c.features_over_cap;
  status.ransac_budget_cuts = c.ransac_budget_cuts;
  const SlamState& state = estimator_.state();
  status.heading_drift_rad_per_m = state.heading_drift_rad_per_m();
  status.heading_drift_sigma_rad_per_m = std::sqrt(std::max(0.0, state.heading_drift_variance()));
  out.PublishMessage(status_channel_, status);
}

std::unique_ptr<Stage> CreateEstimatorStage(const ProcessSettings& settings) {
  return std::make_unique<EstimatorStage>(settings);
}

}  // namespace slammtt
