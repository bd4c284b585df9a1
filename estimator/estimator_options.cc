#include "estimator/estimator_options.h"

namespace slammtt {

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

}  // namespace slammtt
