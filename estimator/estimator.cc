#include "estimator/estimator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "common/utime.h"
#include "estimator/angle.h"
#include "estimator/ekf_prediction.h"
#include "estimator/ekf_update.h"

namespace slammtt {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool AllFinite(const Eigen::Vector3d& v) { return v.allFinite(); }

// The state before the first message (and after a restart): the robot at initial_pose, known
// exactly (it defines the map frame), the heading drift at its prior.
SlamState InitialState(const EstimatorOptions& options) {
  const double drift_sigma = options.heading_drift_sigma_rad_per_m;
  return SlamState(options.initial_pose, Eigen::Matrix3d::Zero(), drift_sigma * drift_sigma);
}

// Which measurement each object got, and the reverse.
struct Assignment {
  std::vector<int> object_of_measurement;
  std::vector<int> measurement_of_object;
  Assignment(int measurements, int objects)
      : object_of_measurement(static_cast<size_t>(measurements), -1),
        measurement_of_object(static_cast<size_t>(objects), -1) {}
  bool MeasurementFree(int i) const { return object_of_measurement[static_cast<size_t>(i)] < 0; }
  bool ObjectFree(int j) const { return measurement_of_object[static_cast<size_t>(j)] < 0; }
  void Set(int i, int j) {
    object_of_measurement[static_cast<size_t>(i)] = j;
    measurement_of_object[static_cast<size_t>(j)] = i;
  }
};

// Applies `pairs` (gated by gate_chi2 at the current state) and records the associated ones.
// A pair whose object may not update this scan (may_update[object] == 0: the static-landmark
// budget) is associated all the same but does not update the state.
int ApplyPairs(const std::vector<Candidate>& pairs,
               const std::vector<PointMeasurement>& measurements, double gate_chi2,
               const std::vector<uint8_t>& may_update, int64_t utime,
               const EstimatorOptions& options, SlamState* state, Assignment* assignment,
               StepCounts* counts) {
  // ApplyObservations skips gated-out pairs; gate here first so that the assignment records
  // exactly the associated pairs.
  const std::vector<ObjectPrediction> predictions = PredictObservations(*state, options.sensor);
  std::vector<ObjectObservation> observations;
  for (const Candidate& c : pairs) {
    if (!assignment->MeasurementFree(c.measurement) || !assignment->ObjectFree(c.object)) continue;
    const PointMeasurement& z = measurements[static_cast<size_t>(c.measurement)];
    const double nis =
        NormalizedInnovationSquared(z, predictions[static_cast<size_t>(c.object)], gate_chi2);
    if (!(nis < gate_chi2)) continue;
    assignment->Set(c.measurement, c.object);
    if (!may_update[static_cast<size_t>(c.object)]) {
      ++counts->static_updates_skipped;
      continue;
    }
    observations.push_back({c.object, z});
    state->object(c.object).record.last_update_utime = utime;
  }
  if (observations.empty()) return 0;
  const UpdateStats stats = ApplyObservations(observations, options.sensor, kInfinity,
                                              options.update_group_size, state);
  counts->updates_failed += stats.failed;
  return stats.applied;
}

// Which objects may update the state this scan: all but the static landmarks beyond the
// budget (EstimatorOptions::max_static_updates_per_scan). The landmarks that have a pair in
// `gated` compete; the least recently updated win, ties to the lower index.
std::vector<uint8_t> ObjectsThatMayUpdate(const SlamState& state,
                                          const std::vector<Candidate>& gated, int budget) {
  const size_t num_objects = static_cast<size_t>(state.num_objects());
  std::vector<uint8_t> may_update(num_objects, 1);
  if (budget <= 0) return may_update;
  std::vector<uint8_t> listed(num_objects, 0);
  std::vector<int> landmarks;
  for (const Candidate& c : gated) {
    const size_t j = static_cast<size_t>(c.object);
    if (listed[j] || state.object(c.object).has_velocity()) continue;
    listed[j] = 1;
    landmarks.push_back(c.object);
  }
  if (static_cast<int>(landmarks.size()) <= budget) return may_update;
  auto staler = [&state](int a, int b) {
    const int64_t ta = state.object(a).record.last_update_utime;
    const int64_t tb = state.object(b).record.last_update_utime;
    return ta != tb ? ta < tb : a < b;
  };
  std::nth_element(landmarks.begin(), landmarks.begin() + budget, landmarks.end(), staler);
  for (size_t k = static_cast<size_t>(budget); k < landmarks.size(); ++k) {
    may_update[static_cast<size_t>(landmarks[k])] = 0;
  }
  return may_update;
}

// Greedy one-to-one choice among pairs in increasing NIS (global nearest neighbour, greedy).
std::vector<Candidate> GreedyOneToOne(std::vector<Candidate> pairs, const Assignment& taken) {
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Candidate& a, const Candidate& b) { return a.nis < b.nis; });
  Assignment local = taken;
  std::vector<Candidate> chosen;
  for (const Candidate& c : pairs) {
    if (!local.MeasurementFree(c.measurement) || !local.ObjectFree(c.object)) continue;
    local.Set(c.measurement, c.object);
    chosen.push_back(c);
  }
  return chosen;
}

}  // namespace

const char* AssociationModeName(AssociationMode mode) {
  switch (mode) {
    case AssociationMode::kMlRansac:
      return "ml_ransac";
    case AssociationMode::kStaticNearestNeighbour:
      return "static_nn";
    case AssociationMode::kRansacAllPairs:
      return "ransac_all_pairs";
  }
  return "?";
}

const char* SubstageName(Substage substage) {
  switch (substage) {
    case Substage::kPredict:
      return "predict";
    case Substage::kGating:
      return "gating";
    case Substage::kLevel1:
      return "level1";
    case Substage::kRansac:
      return "ransac";
    case Substage::kLevel23:
      return "level2_3";
    case Substage::kTrackManagement:
      return "track_management";
  }
  return "?";
}

std::string CheckEstimatorOptions(const EstimatorOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!o.initial_pose.allFinite()) return "initial_pose must be finite";
  if (!std::isfinite(o.sensor.forward_m) || !std::isfinite(o.sensor.left_m)) {
    return "sensor offset must be finite";
  }
  if (!positive(o.default_range_sigma_m)) return "range_sigma_m must be > 0";
  if (!positive(o.default_bearing_sigma_rad)) return "bearing_sigma_deg must be > 0";
  if (!non_negative(o.min_range_sigma_m) || !non_negative(o.min_bearing_sigma_rad)) {
    return "noise floors must be >= 0";
  }
  if (!non_negative(o.min_range_m) || !positive(o.max_range_m) || o.max_range_m <= o.min_range_m) {
    return "need 0 <= min_range_m < max_range_m";
  }
  if (!non_negative(o.detection_range_m)) return "detection_range_m must be >= 0";
  if (!non_negative(o.edge_of_view_sigma_m)) return "edge_of_view_sigma_m must be >= 0";
  if (!positive(o.field_of_view_rad) || o.field_of_view_rad > 2.0 * M_PI + 1e-9) {
    return "field_of_view_deg must be in (0, 360]";
  }
  const OdometryNoiseOptions& n = o.odometry_noise;
  if (!non_negative(n.distance_var_per_m) || !non_negative(n.rotation_var_per_rad) ||
      !non_negative(n.rotation_var_per_m) || !non_negative(n.distance_var_per_s) ||
      !non_negative(n.rotation_var_per_s)) {
    return "odometry noise variances must be >= 0";
  }
  if (!non_negative(o.heading_drift_sigma_rad_per_m) ||
      !non_negative(o.heading_drift_walk_var_per_m)) {
    return "odometry heading drift sigma and walk variance must be >= 0";
  }
  if (!non_negative(o.mover_acceleration_sigma_mps2) ||
      !non_negative(o.undecided_acceleration_sigma_mps2)) {
    return "acceleration sigmas must be >= 0";
  }
  if (!positive(o.new_object_velocity_sigma_mps)) return "new_object_velocity_sigma must be > 0";
  if (!non_negative(o.manoeuvre_velocity_sigma_mps)) return "manoeuvre_velocity_sigma must be >= 0";
  if (!positive(o.max_time_gap_s)) return "max_time_gap_s must be > 0";
  if (!positive(o.max_prediction_s) || o.max_prediction_s < o.max_time_gap_s) {
    return "max_prediction_s must be >= max_time_gap_s and > 0";
  }
  if (!positive(o.time_jump_back_restart_s)) return "time_jump_back_restart_s must be > 0";
  if (!non_negative(o.gap_robot_position_sigma_mps) ||
      !non_negative(o.gap_robot_heading_sigma_radps) ||
      !non_negative(o.gap_mover_velocity_sigma_mps) ||
      !non_negative(o.extrapolation_speed_sigma_mps) ||
      !non_negative(o.extrapolation_turn_sigma_radps)) {
    return "inflation sigmas must be >= 0";
  }
  if (o.max_objects < 0) return "max_objects must be >= 0";
  if (!positive(o.gate_d1_chi2)) return "gate_d1 must be > 0";
  if (o.level3 && !(o.gate_d2_chi2 > o.gate_d1_chi2 && std::isfinite(o.gate_d2_chi2))) {
    return "gate_d2 must be > gate_d1";
  }
  if (!positive(o.new_object_gate_dn_chi2)) return "gate_dn must be > 0";
  if (!(o.ransac.success_probability > 0.0 && o.ransac.success_probability < 1.0)) {
    return "ransac_probability must be in (0, 1)";
  }
  if (o.ransac.max_hypotheses < 1) return "max_hypotheses must be >= 1";
  if (!positive(o.ransac.inlier_chi2)) return "ransac_inlier_chi2 must be > 0";
  if (o.update_group_size < 1) return "update_group_size must be >= 1";
  if (o.max_static_updates_per_scan < 0) return "max_static_updates_per_scan must be >= 0";
  if (o.tracks.confirm_hits < 1) return "confirm_hits must be >= 1";
  if (!non_negative(o.tracks.prune_unseen_s) || !non_negative(o.tracks.tentative_prune_unseen_s) ||
      !non_negative(o.tracks.static_prune_unseen_in_view_s) ||
      !non_negative(o.tracks.prune_unseen_visible_s) || !non_negative(o.tracks.shadow_radius_m) ||
      !non_negative(o.tracks.coast_confirmed_s) || !non_negative(o.tracks.coast_unseen_s) ||
      !non_negative(o.tracks.prune_out_of_view_s) || !positive(o.tracks.max_coast_sigma_m) ||
      !non_negative(o.tracks.reacquire_speed_mps)) {
    return "prune times must be >= 0";
  }
  const MotionClassifierOptions& c = o.classifier;
  if (!non_negative(c.moving_chi2) || !non_negative(c.moving_min_speed_mps) ||
      !non_negative(c.still_max_speed_mps) || !non_negative(c.still_hold_s) ||
      !non_negative(c.still_velocity_chi2) || !non_negative(c.still_restart_variance_ratio) ||
      !positive(c.started_moving_chi2)) {
    return "classifier thresholds must be >= 0";
  }
  if (c.moving_confirm_scans < 1) return "moving_confirm_scans must be >= 1";
  return "";
}

Estimator::Estimator(const EstimatorOptions& options)
    : options_(options), state_(InitialState(options)) {}

bool Estimator::RestartOnJumpBack(const char* what, int64_t utime,
                                  const std::optional<int64_t>& newest_utime) {
  if (!newest_utime) return false;
  const double back_s = SecondsBetween(*newest_utime, utime);
  if (!(back_s > options_.time_jump_back_restart_s)) return false;
  ++counters_.restarts;
  std::ostringstream text;
  text << what << " at utime " << utime << " is " << back_s << " s older than the newest ("
       << *newest_utime << "): a new time base, estimation started over";
  Event(text.str());
  state_ = InitialState(options_);
  last_scan_utime_.reset();
  last_odometry_utime_.reset();
  cursor_.reset();
  odometry_.clear();
  return true;
}

bool Estimator::AddOdometry(const OdometryReading& reading) {
  if (!AllFinite(reading.pose) || !std::isfinite(reading.linear_mps) ||
      !std::isfinite(reading.angular_radps)) {
    ++counters_.odometry_rejected;
    Event("odometry at utime " + std::to_string(reading.utime) + " rejected: not finite");
    return false;
  }
  RestartOnJumpBack("odometry", reading.utime, last_odometry_utime_);
  if (last_odometry_utime_ && reading.utime <= *last_odometry_utime_) {
    ++counters_.messages_out_of_order;
    Event("odometry at utime " + std::to_string(reading.utime) +
          " dropped: not newer than the last one (" + std::to_string(*last_odometry_utime_) + ")");
    return false;
  }
  last_odometry_utime_ = reading.utime;
  ++counters_.odometry_processed;
  OdometryReading r = reading;
  r.pose(2) = WrapAngle(r.pose(2));
  if (!cursor_) {
    // The first reading anchors the odometry: motion is measured from here on.
    cursor_ = OdometryCursor{r.utime, r.pose, r.linear_mps, r.angular_radps};
    return true;
  }
  if (r.utime <= cursor_->utime) {
    // Late reading (older than the last scan): its velocities are the freshest we have.
    cursor_->linear_mps = r.linear_mps;
    cursor_->angular_radps = r.angular_radps;
    return true;
  }
  odometry_.push_back(r);
  return true;
}

void Estimator::Predict(int64_t utime, bool first_scan, double gap_s, double dt) {
  // With the drift state off its variance stays exactly 0 (no random walk), so b stays 0.
  const double drift_walk_var_per_m =
      options_.heading_drift_sigma_rad_per_m > 0.0 ? options_.heading_drift_walk_var_per_m : 0.0;
  RobotMotionAccumulator motion(state_.robot_pose(), state_.heading_drift_rad_per_m(),
                                drift_walk_var_per_m);
  const double speed_var_rate = options_.extrapolation_speed_sigma_mps *
                                options_.extrapolation_speed_sigma_mps;
  const double turn_var_rate = options_.extrapolation_turn_sigma_radps *
                               options_.extrapolation_turn_sigma_radps;
  bool had_odometry = false;
  if (cursor_) {
    OdometryCursor previous = *cursor_;
    while (!odometry_.empty() && odometry_.front().utime <= utime) {
      const OdometryReading& r = odometry_.front();
      const OdometryIncrement increment = IncrementBetweenOdometryPoses(previous.pose, r.pose);
      motion.Add(increment,
                 OdometryIncrementCovariance(increment, SecondsBetween(r.utime, previous.utime),
                                             options_.odometry_noise));
      previous = OdometryCursor{r.utime, r.pose, r.linear_mps, r.angular_radps};
      odometry_.pop_front();
      had_odometry = true;
    }
    if (!odometry_.empty()) {
      // The scan falls between two readings: the part of the next increment up to the scan.
      const OdometryReading& next = odometry_.front();
      const double fraction = MicrosecondsBetween(utime, previous.utime) /
                              MicrosecondsBetween(next.utime, previous.utime);
      const OdometryIncrement full = IncrementBetweenOdometryPoses(previous.pose, next.pose);
      const OdometryIncrement part{fraction * full.distance_m, fraction * full.rotation_rad};
      motion.Add(part, OdometryIncrementCovariance(part, SecondsBetween(utime, previous.utime),
                                                   options_.odometry_noise));
      cursor_ = OdometryCursor{utime, PredictRobotPose(previous.pose, part), next.linear_mps,
                               next.angular_radps};
      had_odometry = true;
    } else {
      // No reading at or after the scan yet: extrapolate with the last velocities, with noise
      // that grows with the extrapolated time.
      const double tau =
          std::min(SecondsBetween(utime, previous.utime), options_.max_prediction_s);
      const OdometryIncrement part{previous.linear_mps * tau, previous.angular_radps * tau};
      Eigen::Matrix2d covariance =
          OdometryIncrementCovariance(part, tau, options_.odometry_noise);
      covariance(0, 0) += speed_var_rate * tau * tau;
      covariance(1, 1) += turn_var_rate * tau * tau;
      motion.Add(part, covariance);
      cursor_ = OdometryCursor{utime, PredictRobotPose(previous.pose, part), previous.linear_mps,
                               previous.angular_radps};
    }
  } else if (!first_scan) {
    // No odometry ever: a robot standing still, with the extrapolation noise.
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    covariance(0, 0) = speed_var_rate * dt * dt;
    covariance(1, 1) = turn_var_rate * dt * dt;
    motion.Add(OdometryIncrement{}, covariance);
  }
  if (!first_scan && !had_odometry) {
    ++counters_.scans_without_odometry;
    Event("scan at utime " + std::to_string(utime) +
          ": no odometry since the previous scan, predicted with the last velocity");
  }
  if (gap_s > options_.max_time_gap_s) {
    ++counters_.time_gaps;
    std::ostringstream text;
    text << "scan at utime " << utime << ": " << gap_s << " s since the previous scan (limit "
         << options_.max_time_gap_s << " s), uncertainty inflated";
    if (gap_s > dt) text << " as for " << dt << " s";
    Event(text.str());
    const double position_sigma = options_.gap_robot_position_sigma_mps * dt;
    // A heading known to within more than half a turn is not known at all.
    const double heading_sigma = std::min(options_.gap_robot_heading_sigma_radps * dt, M_PI);
    motion.AddPoseNoise(Eigen::Vector3d(position_sigma * position_sigma,
                                        position_sigma * position_sigma,
                                        heading_sigma * heading_sigma)
                            .asDiagonal());
    const double velocity_sigma = options_.gap_mover_velocity_sigma_mps;
    InflateMoverVelocities(velocity_sigma * velocity_sigma * Eigen::Matrix2d::Identity(), &state_);
  }
  // The map frame is the robot's pose at the first message, so the motion between the first
  // odometry reading and the first scan counts too.
  ApplyRobotPrediction(motion.pose(), motion.jacobian(), motion.noise(), &state_);
  if (dt > 0.0) {
    PredictMovers(dt, options_.mover_acceleration_sigma_mps2,
                  options_.undecided_acceleration_sigma_mps2, &state_);
  }
}

std::vector<PointMeasurement> Estimator::ValidateFeatures(
    const std::vector<FeatureReading>& features, StepCounts* counts, std::vector<double>* widths) {
  std::vector<PointMeasurement> measurements;
  measurements.reserve(features.size());
  const double default_range_var = options_.default_range_sigma_m * options_.default_range_sigma_m;
  const double default_bearing_var =
      options_.default_bearing_sigma_rad * options_.default_bearing_sigma_rad;
  int rejected = 0;
  std::string first_reason;
  for (const FeatureReading& f : features) {
    std::string reason;
    if (!std::isfinite(f.range_m) || !std::isfinite(f.bearing_rad) ||
        !std::isfinite(f.range_var_m2) || !std::isfinite(f.bearing_var_rad2) ||
        !std::isfinite(f.range_bearing_cov_m_rad)) {
      reason = "not finite";
    } else if (f.range_m < options_.min_range_m || f.range_m > options_.max_range_m) {
      reason = "range " + std::to_string(f.range_m) + " m out of [" +
               std::to_string(options_.min_range_m) + ", " + std::to_string(options_.max_range_m) +
               "] m";
    } else if (std::abs(f.bearing_rad) > M_PI + 1e-9) {
      reason = "bearing " + std::to_string(f.bearing_rad) + " rad out of [-pi, pi]";
    } else if (f.range_var_m2 < 0.0 || f.bearing_var_rad2 < 0.0 ||
               f.range_bearing_cov_m_rad * f.range_bearing_cov_m_rad >
                   f.range_var_m2 * f.bearing_var_rad2) {
      reason = "covariance not positive semi-definite";
    }
    if (!reason.empty()) {
      ++rejected;
      if (first_reason.empty()) first_reason = reason;
      continue;
    }
    PointMeasurement m;
    m.range_bearing = Eigen::Vector2d(f.range_m, WrapAngle(f.bearing_rad));
    if (options_.use_feature_covariance && f.range_var_m2 > 0.0 && f.bearing_var_rad2 > 0.0) {
      m.covariance << f.range_var_m2, f.range_bearing_cov_m_rad, f.range_bearing_cov_m_rad,
          f.bearing_var_rad2;
      m.covariance(0, 0) = std::max(m.covariance(0, 0),
                                    options_.min_range_sigma_m * options_.min_range_sigma_m);
      m.covariance(1, 1) = std::max(m.covariance(1, 1),
                                    options_.min_bearing_sigma_rad * options_.min_bearing_sigma_rad);
    } else {
      m.covariance << default_range_var, 0.0, 0.0, default_bearing_var;
    }
    const double width = std::isfinite(f.width_m) && f.width_m > 0.0 ? f.width_m : 0.0;
    if (options_.edge_of_view_sigma_m > 0.0 && options_.field_of_view_rad < 2.0 * M_PI) {
      const double range = m.range_bearing(0);
      const double extent = std::atan2(0.5 * width, range);
      if (std::abs(m.range_bearing(1)) + extent + kEdgeOfViewMargin_rad >=
          0.5 * options_.field_of_view_rad) {
        const double s = options_.edge_of_view_sigma_m;
        // s across the line of sight is s / range in bearing, at most pi: a bearing cannot be
        // more uncertain than the half circle, and a feature at the sensor (min_range_m 0)
        // must not get an infinite variance.
        const double bearing_sigma = std::min(s / range, M_PI);
        m.covariance(0, 0) += s * s;
        m.covariance(1, 1) += bearing_sigma * bearing_sigma;
        ++counts->features_at_edge_of_view;
      }
    }
    measurements.push_back(m);
    widths->push_back(width);
  }
  if (rejected > 0) {
    counts->features_rejected = rejected;
    counters_.features_rejected += rejected;
    Event(std::to_string(rejected) + " feature(s) rejected, first: " + first_reason);
  }
  return measurements;
}

ScanResult Estimator::ProcessScan(const ScanInput& scan, std::mt19937_64* rng,
                                  StepObserver* observer) {
  ScanResult result;
  result.utime = scan.utime;
  StepCounts& counts = result.counts;
  counts.features = static_cast<int>(scan.features.size());
  auto lap = [observer](Substage s) {
    if (observer != nullptr) observer->SubstageDone(s);
  };
  RestartOnJumpBack("scan", scan.utime, last_scan_utime_);
  if (last_scan_utime_ && scan.utime <= *last_scan_utime_) {
    ++counters_.messages_out_of_order;
    Event("scan at utime " + std::to_string(scan.utime) +
          " dropped: not newer than the last processed scan (" +
          std::to_string(*last_scan_utime_) + ")");
    return result;
  }
  const bool first_scan = !last_scan_utime_;
  // Time since the previous scan (what went unseen) and the part of it the prediction covered
  // (max_prediction_s), over which a manoeuvre's velocity jump acts.
  const double gap_s = first_scan ? 0.0 : SecondsBetween(scan.utime, *last_scan_utime_);
  const double dt = std::min(gap_s, options_.max_prediction_s);

  // --- predict (line 2)
  std::vector<double> widths;
  const std::vector<PointMeasurement> measurements =
      ValidateFeatures(scan.features, &counts, &widths);
  Predict(scan.utime, first_scan, gap_s, dt);
  last_scan_utime_ = scan.utime;
  lap(Substage::kPredict);

  // --- gating (lines 3-4). Pairs are kept up to the widest gate any later step asks about.
  const int num_measurements = static_cast<int>(measurements.size());
  const int num_objects_before = state_.num_objects();
  const double d1 = options_.gate_d1_chi2;
  const double dn = options_.new_object_gate_dn_chi2;
  const double widest = std::max({d1, dn, options_.level3 ? options_.gate_d2_chi2 : 0.0});
  std::vector<ObjectPrediction> predictions = PredictObservations(state_, options_.sensor);
  const std::vector<Candidate> gated = GatePairs(measurements, predictions, widest);
  std::vector<double> nearest_nis(static_cast<size_t>(num_measurements), kInfinity);
  std::vector<Candidate> compatible;  // J
  for (const Candidate& c : gated) {
    double& nearest = nearest_nis[static_cast<size_t>(c.measurement)];
    nearest = std::min(nearest, c.nis);
    if (c.nis < d1) compatible.push_back(c);
  }
  lap(Substage::kGating);

  Assignment assignment(num_measurements, num_objects_before);
  const std::vector<uint8_t> may_update =
      ObjectsThatMayUpdate(state_, gated, options_.max_static_updates_per_scan);
  if (options_.mode == AssociationMode::kStaticNearestNeighbour) {
    // --- nearest neighbour: each measurement's closest object in d1, one-to-one.
    std::vector<Candidate> nearest;
    for (const Candidate& c : compatible) {
      if (nearest.empty() || nearest.back().measurement != c.measurement) {
        nearest.push_back(c);
      } else if (c.nis < nearest.back().nis) {
        nearest.back() = c;
      }
    }
    counts.level1_updates = ApplyPairs(GreedyOneToOne(nearest, assignment), measurements, d1,
                                       may_update, scan.utime, options_, &state_, &assignment,
                                       &counts);
    lap(Substage::kLevel1);
    lap(Substage::kRansac);
  } else {
    std::vector<Candidate> sample_space;
    if (options_.mode == AssociationMode::kMlRansac) {
      // --- level 1 (lines 5-6)
      const CompatibilitySplit split =
          SplitCompatibility(compatible, num_measurements, num_objects_before);
      counts.level1_updates = ApplyPairs(split.unambiguous, measurements, d1, may_update,
                                         scan.utime, options_, &state_, &assignment, &counts);
      lap(Substage::kLevel1);
      // --- RANSAC over what J leaves ambiguous (line 7), re-judged at the updated state.
      if (!split.ambiguous.empty()) {
        predictions = PredictObservations(state_, options_.sensor);
        for (const Candidate& c : split.ambiguous) {
          if (!assignment.MeasurementFree(c.measurement) || !assignment.ObjectFree(c.object)) {
            continue;
          }
          const double nis = NormalizedInnovationSquared(
              measurements[static_cast<size_t>(c.measurement)],
              predictions[static_cast<size_t>(c.object)], d1);
          if (nis < d1) sample_space.push_back({c.measurement, c.object, nis});
        }
      }
    } else {
      lap(Substage::kLevel1);
      // Plain RANSAC: every pair is a possible hypothesis.
      for (int i = 0; i < num_measurements; ++i) {
        for (int j = 0; j < num_objects_before; ++j) {
          const double nis = NormalizedInnovationSquared(
              measurements[static_cast<size_t>(i)], predictions[static_cast<size_t>(j)], kInfinity);
          if (std::isfinite(nis)) sample_space.push_back({i, j, nis});
        }
      }
    }
    RansacOutcome ransac;
    if (!sample_space.empty()) {
      ransac = RunOnePointRansac(state_, measurements, predictions, sample_space, sample_space,
                                 options_.sensor, options_.ransac, rng);
    }
    counts.hypotheses = ransac.hypotheses;
    counters_.hypotheses_generated += ransac.hypotheses;
    lap(Substage::kRansac);
    // --- level 2: the best hypothesis' pairs, gated by d1 (line 7.e)
    counts.level2_updates = ApplyPairs(ransac.consensus, measurements, d1, may_update,
                                       scan.utime, options_, &state_, &assignment, &counts);
  }
  // --- level 3 (line 9): what is left, with the wider gate d2
  if (options_.level3 && options_.mode != AssociationMode::kStaticNearestNeighbour) {
    // Manoeuvres: an unassigned MOVING object with an unassigned measurement inside its gate
    // dn as it would be after the velocity jump (undecided objects still have their wide
    // velocity prior). The jump adds (sigma dt)^2 I to the position covariance (ekf_prediction.h:
    // AddVelocityJump), so the gate is judged with that added: a person who stops dead is
    // outside the gate of the steady walk within a few scans, inside the manoeuvre's.
    if (options_.manoeuvre_velocity_sigma_mps > 0.0 && dt > 0.0) {
      const double jump_m = options_.manoeuvre_velocity_sigma_mps * dt;
      const std::vector<ObjectPrediction> now = PredictObservations(state_, options_.sensor);
      for (int j = 0; j < num_objects_before; ++j) {
        const StateObject& object = state_.object(j);
        const ObjectPrediction& p = now[static_cast<size_t>(j)];
        if (!assignment.ObjectFree(j) || !object.has_velocity() || !p.valid ||
            object.record.object_class != ObjectClass::kMoving) {
          continue;
        }
        ObjectPrediction widened = p;
        widened.hph += jump_m * jump_m * p.jacobian_position * p.jacobian_position.transpose();
        for (int i = 0; i < num_measurements; ++i) {
          if (!assignment.MeasurementFree(i)) continue;
          if (NormalizedInnovationSquared(measurements[static_cast<size_t>(i)], widened, dn) < dn) {
            AddVelocityJump(j, dt, options_.manoeuvre_velocity_sigma_mps, &state_);
            ++counts.manoeuvres;
            break;
          }
        }
      }
    }
    predictions = PredictObservations(state_, options_.sensor);
    std::vector<int> free_measurements;
    std::vector<int> free_objects;
    for (int i = 0; i < num_measurements; ++i) {
      if (assignment.MeasurementFree(i)) free_measurements.push_back(i);
    }
    for (int j = 0; j < num_objects_before; ++j) {
      if (assignment.ObjectFree(j)) free_objects.push_back(j);
    }
    std::vector<Candidate> remaining;
    if (free_measurements.size() * free_objects.size() <= kGatingBruteForcePairs) {
      for (int i : free_measurements) {
        for (int j : free_objects) {
          const double nis = NormalizedInnovationSquared(measurements[static_cast<size_t>(i)],
                                                         predictions[static_cast<size_t>(j)],
                                                         options_.gate_d2_chi2);
          if (nis < options_.gate_d2_chi2) remaining.push_back({i, j, nis});
        }
      }
    } else {
      // Same pairs, same order, looked up by bearing (gating.h).
      for (const Candidate& c : GatePairs(measurements, predictions, options_.gate_d2_chi2)) {
        if (assignment.MeasurementFree(c.measurement) && assignment.ObjectFree(c.object)) {
          remaining.push_back(c);
        }
      }
    }
    // Choose by PairCost (gating.h): a wide object must not win a measurement from a
    // well-known one merely by its smaller NIS. GreedyOneToOne orders by the `nis` field, so it
    // carries the cost from here on (ApplyPairs re-gates by the NIS itself).
    for (Candidate& c : remaining) {
      c.nis = PairCost(measurements[static_cast<size_t>(c.measurement)],
                       predictions[static_cast<size_t>(c.object)], c.nis);
    }
    counts.level3_updates =
        ApplyPairs(GreedyOneToOne(std::move(remaining), assignment), measurements,
                   options_.gate_d2_chi2, may_update, scan.utime, options_, &state_, &assignment,
                   &counts);
  }
  lap(Substage::kLevel23);

  // --- track management (lines 11-13)
  // Baseline (a) is plain EKF-SLAM: every landmark is part of the map from its first sighting
  // and stays in it; no miss accounting, classification or pruning.
  const bool static_world = options_.mode == AssociationMode::kStaticNearestNeighbour;
  // Hits and misses; a miss counts towards pruning faster when the object should have been
  // seen (in view, not behind anything this scan saw).
  std::vector<Eigen::Vector3d> seen;
  seen.reserve(measurements.size());
  for (size_t i = 0; i < measurements.size(); ++i) {
    seen.emplace_back(measurements[i].range_bearing(0), measurements[i].range_bearing(1),
                      widths[i]);
  }
  const std::vector<ObjectPrediction> after_updates = PredictObservations(state_, options_.sensor);
  const double detection_range =
      options_.detection_range_m > 0.0 ? options_.detection_range_m : options_.max_range_m;
  for (int j = 0; j < num_objects_before; ++j) {
    ObjectRecord& record = state_.object(j).record;
    if (!assignment.ObjectFree(j)) {
      RecordHit(scan.utime, options_.tracks, &record);
      record.last_seen_m = state_.position(j);
    } else if (!static_world) {
      const ObjectPrediction& p = after_updates[static_cast<size_t>(j)];
      const StateObject& object = state_.object(j);
      const Eigen::Matrix2d position_cov =
          state_.covariance().block<2, 2>(object.position_index, object.position_index);
      const double sigma = std::sqrt(std::max(position_cov(0, 0), position_cov(1, 1)));
      const bool in_geometry =
          p.valid && SurelyInGeometry(p.range_bearing, sigma, options_.max_range_m,
                                      options_.field_of_view_rad);
      RecordMiss(gap_s, in_geometry,
                 in_geometry && ExpectedVisible(p.range_bearing, sigma, seen, detection_range,
                                                options_.field_of_view_rad,
                                                options_.tracks.shadow_radius_m),
                 &record);
    }
  }
  // Re-acquisition of lost movers, second step (track_management.h): a tentative object born
  // as the possible continuation of a lost track takes over its identity and MOVING label at
  // its second measurement, if the lost track is still lost.
  std::vector<int> taken_over;  // lost tracks whose identity moved to a new object
  for (int k = 0; k < num_objects_before; ++k) {
    ObjectRecord& candidate = state_.object(k).record;
    // (Not "still tentative": with confirm_hits <= 2 its own second hit has just confirmed it.)
    if (candidate.continues_id == 0 || assignment.ObjectFree(k) || candidate.hits < 2) continue;
    const int64_t lost_id = candidate.continues_id;
    candidate.continues_id = 0;
    for (int j = 0; j < num_objects_before; ++j) {
      const StateObject& lost = state_.object(j);
      if (lost.record.id != lost_id) continue;
      if (IsLostMover(lost, assignment.ObjectFree(j), scan.utime, options_.tracks) &&
          std::find(taken_over.begin(), taken_over.end(), j) == taken_over.end()) {
        candidate.id = lost.record.id;
        candidate.first_seen_utime = lost.record.first_seen_utime;
        candidate.hits += lost.record.hits;
        candidate.confirmed = true;
        candidate.object_class = ObjectClass::kMoving;
        taken_over.push_back(j);
        ++counts.reacquired;
      }
      break;
    }
  }
  // Classification (line 12).
  if (!static_world) {
    // For static landmarks: the measurement that speaks about each (its own, or else the
    // nearest unassociated one inside gate dn), judged at the state after the updates.
    std::vector<int> landmark_measurement(static_cast<size_t>(num_objects_before), -1);
    std::vector<double> landmark_nis(static_cast<size_t>(num_objects_before), kInfinity);
    for (const Candidate& c : gated) {
      if (state_.object(c.object).has_velocity()) continue;
      const int assigned = assignment.object_of_measurement[static_cast<size_t>(c.measurement)];
      const size_t j = static_cast<size_t>(c.object);
      if (assigned == c.object) {
        landmark_measurement[j] = c.measurement;
        landmark_nis[j] = -1.0;  // its own measurement wins
      } else if (assigned < 0 && assignment.ObjectFree(c.object) && c.nis < dn &&
                 c.nis < landmark_nis[j]) {
        landmark_measurement[j] = c.measurement;
        landmark_nis[j] = c.nis;
      }
    }
    const std::vector<ObjectPrediction>& judged = after_updates;
    for (int j = 0; j < num_objects_before; ++j) {
      StateObject& object = state_.object(j);
      ObjectRecord& record = object.record;
      if (object.has_velocity()) {
        const Eigen::Matrix2d velocity_cov =
            state_.covariance().block<2, 2>(object.velocity_index, object.velocity_index);
        const Eigen::Matrix2d position_cov =
            state_.covariance().block<2, 2>(object.position_index, object.position_index);
        const ClassChange change =
            ClassifyMover(state_.position(j), position_cov, state_.velocity(j), velocity_cov,
                          scan.utime, options_.classifier, &record);
        if (change == ClassChange::kBecameMoving) {
          record.class_change_utime = scan.utime;
          ++counts.became_moving;
        } else if (change == ClassChange::kBecameStatic) {
          state_.RemoveVelocityAssumingZero(j);
          ObjectRecord& r = state_.object(j).record;
          r.object_class = ObjectClass::kStatic;
          r.class_change_utime = scan.utime;
          r.moving_evidence_scans = 0;
          ClearLandmarkEvidence(&r);
          ++counts.became_static;
        }
        continue;
      }
      const int i = landmark_measurement[static_cast<size_t>(j)];
      const ObjectPrediction& prediction = judged[static_cast<size_t>(j)];
      if (i < 0 || !prediction.valid) continue;
      const PointMeasurement& z = measurements[static_cast<size_t>(i)];
      const Eigen::Vector2d measured = PointFromRangeBearing(state_.robot_pose(), z.range_bearing,
                                                             options_.sensor);
      const Eigen::Matrix2d to_map = prediction.jacobian_position.inverse();
      const Eigen::Matrix2d covariance =
          to_map * (prediction.hph + z.covariance) * to_map.transpose();
      if (ClassifyLandmark(measured - state_.position(j), covariance, options_.classifier,
                           &record) == ClassChange::kStartedMoving) {
        const double sigma = options_.new_object_velocity_sigma_mps;
        state_.AddVelocity(j, Eigen::Vector2d::Zero(), sigma * sigma * Eigen::Matrix2d::Identity());
        ObjectRecord& r = state_.object(j).record;
        r.object_class = ObjectClass::kUndecided;
        r.class_change_utime = scan.utime;
        r.moving_evidence_scans = 0;
        RestartStillWindow(
            state_.position(j),
            LargestEigenvalue(state_.covariance().block<2, 2>(object.position_index,
                                                              object.position_index)),
            scan.utime, &r);
        ++counts.started_moving;
      }
    }
  }
  // Re-acquisition of lost movers, first step: which lost track each measurement that starts
  // a new object may continue.
  std::vector<int64_t> continues_id_of_measurement(static_cast<size_t>(num_measurements), 0);
  if (!static_world && options_.tracks.reacquire_speed_mps > 0.0) {
    std::vector<LostTrack> lost;
    for (int j = 0; j < num_objects_before; ++j) {
      const StateObject& object = state_.object(j);
      if (!IsLostMover(object, assignment.ObjectFree(j), scan.utime, options_.tracks) ||
          std::find(taken_over.begin(), taken_over.end(), j) != taken_over.end()) {
        continue;
      }
      lost.push_back({j, object.record.last_seen_m,
                      SecondsBetween(scan.utime, object.record.last_seen_utime)});
    }
    std::vector<BirthPoint> births;
    if (!lost.empty()) {
      // A static landmark that got no measurement this scan and lies within twice the
      // new-object gate of a measurement has most likely produced it, with an error out in the
      // tail (s1-crossing's point features: 0.9 m in range at 18 m, 4.6 sigma): such a
      // measurement is not trusted to carry an identity.
      std::vector<int> unmeasured_landmarks;
      for (int j = 0; j < num_objects_before; ++j) {
        if (assignment.ObjectFree(j) && !state_.object(j).has_velocity()) {
          unmeasured_landmarks.push_back(j);
        }
      }
      const std::vector<ObjectPrediction> now = PredictObservations(state_, options_.sensor);
      for (int i = 0; i < num_measurements; ++i) {
        if (!assignment.MeasurementFree(i) || nearest_nis[static_cast<size_t>(i)] < dn) continue;
        const PointMeasurement& z = measurements[static_cast<size_t>(i)];
        const bool landmark_outlier = std::any_of(
            unmeasured_landmarks.begin(), unmeasured_landmarks.end(), [&](int j) {
              return NormalizedInnovationSquared(z, now[static_cast<size_t>(j)], 2.0 * dn) <
                     2.0 * dn;
            });
        if (landmark_outlier) continue;
        births.push_back({i, PointFromRangeBearing(
                                 state_.robot_pose(),
                                 measurements[static_cast<size_t>(i)].range_bearing,
                                 options_.sensor)});
      }
    }
    for (const Reacquisition& r :
         ChooseReacquisitions(lost, births, options_.tracks.reacquire_speed_mps)) {
      continues_id_of_measurement[static_cast<size_t>(r.measurement)] =
          state_.object(r.object).record.id;
    }
  }
  // Pruning (line 11).
  std::vector<int> prune;
  for (int j = 0; j < (static_world ? 0 : num_objects_before); ++j) {
    const StateObject& object = state_.object(j);
    const ObjectPrediction& p = after_updates[static_cast<size_t>(j)];
    // Outside the sensor's geometry (not merely too far for the segmenter to see a person).
    const bool out_of_view = !p.valid || p.range_bearing(0) > options_.max_range_m ||
                             std::abs(p.range_bearing(1)) > 0.5 * options_.field_of_view_rad;
    const Eigen::Matrix2d position_cov =
        state_.covariance().block<2, 2>(object.position_index, object.position_index);
    const double position_sigma = std::sqrt(std::max(position_cov(0, 0), position_cov(1, 1)));
    if (ShouldPrune(object.record, object.has_velocity(), scan.utime, out_of_view,
                    position_sigma, options_.tracks)) {
      prune.push_back(j);
    }
  }
  counts.pruned = static_cast<int>(prune.size());
  // A lost track whose identity went to a new object goes.
  for (int j : taken_over) {
    if (std::find(prune.begin(), prune.end(), j) == prune.end()) prune.push_back(j);
  }
  state_.RemoveObjects(prune);
  // New objects (line 13): unassigned measurements outside gate dn of every object.
  for (int i = 0; i < num_measurements; ++i) {
    if (!assignment.MeasurementFree(i) || nearest_nis[static_cast<size_t>(i)] < dn) continue;
    if (state_.num_objects() >= options_.max_objects) {
      ++counts.objects_refused;
      continue;
    }
    const PointMeasurement& z = measurements[static_cast<size_t>(i)];
    Eigen::Matrix<double, 2, 3> jacobian_robot;
    Eigen::Matrix2d jacobian_measurement;
    const Eigen::Vector2d position = PointFromRangeBearing(
        state_.robot_pose(), z.range_bearing, options_.sensor, &jacobian_robot,
        &jacobian_measurement);
    ObjectRecord record = NewObjectRecord(
        next_id_++, scan.utime, static_world ? ObjectClass::kStatic : ObjectClass::kUndecided);
    RestartStillWindow(position, kInfinity, scan.utime, &record);
    record.confirmed = static_world;  // plain EKF-SLAM maps a landmark at its first sighting
    record.last_seen_m = position;
    record.continues_id = continues_id_of_measurement[static_cast<size_t>(i)];
    const int k = state_.AddObject(position, jacobian_robot,
                                   jacobian_measurement * z.covariance *
                                       jacobian_measurement.transpose(),
                                   record);
    if (!static_world) {
      const double sigma = options_.new_object_velocity_sigma_mps;
      state_.AddVelocity(k, Eigen::Vector2d::Zero(), sigma * sigma * Eigen::Matrix2d::Identity());
    }
    ++counts.new_objects;
  }
  if (counts.objects_refused > 0) {
    counters_.object_cap_hits += counts.objects_refused;
    Event("scan at utime " + std::to_string(scan.utime) + ": " +
          std::to_string(counts.objects_refused) + " new object(s) refused, cap of " +
          std::to_string(options_.max_objects) + " objects reached");
  }
  counters_.static_updates_skipped += counts.static_updates_skipped;
  if (counts.updates_failed > 0) {
    counters_.updates_failed += counts.updates_failed;
    Event("scan at utime " + std::to_string(scan.utime) + ": " +
          std::to_string(counts.updates_failed) + " observation(s) numerically unusable");
  }
  lap(Substage::kTrackManagement);

  ++counters_.scans_processed;
  result.processed = true;
  result.pose = state_.robot_pose();
  result.pose_covariance = state_.robot_covariance();
  result.objects.reserve(static_cast<size_t>(state_.num_objects()));
  for (int j = 0; j < state_.num_objects(); ++j) {
    const ObjectRecord& record = state_.object(j).record;
    ObjectEstimate e;
    e.id = record.id;
    e.object_class = record.object_class;
    e.confirmed = ReportedConfirmed(record, state_.object(j).has_velocity(), scan.utime,
                                    options_.tracks);
    e.position = state_.position(j);
    e.velocity = state_.velocity(j);
    e.covariance = state_.ObjectCovariance(j);
    e.first_seen_utime = record.first_seen_utime;
    e.last_seen_utime = record.last_seen_utime;
    e.hits = record.hits;
    result.objects.push_back(e);
  }
  return result;
}

int Estimator::NumObjectsOfClass(ObjectClass object_class, bool confirmed_only) const {
  int n = 0;
  for (const StateObject& o : state_.objects()) {
    if (o.record.object_class == object_class && (o.record.confirmed || !confirmed_only)) ++n;
  }
  return n;
}

int Estimator::NumTentative() const {
  int n = 0;
  for (const StateObject& o : state_.objects()) n += o.record.confirmed ? 0 : 1;
  return n;
}

}  // namespace slammtt
