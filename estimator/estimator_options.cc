#include "estimator/estimator_options.h"

#include <algorithm>

namespace slammtt {

FieldOfView FieldOfViewOf(const EstimatorOptions& options) {
  FieldOfView view;
  if (options.field_of_view_start_rad != 0.0 || options.field_of_view_end_rad != 0.0) {
    view.start_rad = options.field_of_view_start_rad;
    view.end_rad = options.field_of_view_end_rad;
    view.symmetric = false;
  } else {
    view.start_rad = -0.5 * options.field_of_view_rad;
    view.end_rad = 0.5 * options.field_of_view_rad;
  }
  return view;
}

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

namespace {

// The sensor and the features taken from it.
void VisitSensorOptions(OptionVisitor* v, EstimatorOptions* o) {
  using R = OptionRange;
  const OptionUnit deg = OptionUnit::kDegrees;
  v->BeginGroup("sensor");
  v->Double("forward_m", &o->sensor.forward_m, R::Any(), "laser ahead of the axle centre (a)");
  v->Double("left_m", &o->sensor.left_m, R::Any(), "laser left of the axle centre (b)");
  v->Double("yaw_rad", &o->sensor.yaw_rad, R::Between(-180, 180),
            "the laser's heading, CCW from the robot's (a rotated mount)", deg);
  v->EndGroup();
  v->Double("default_range_sigma_m", &o->default_range_sigma_m, R::Above(0),
            "range noise of a feature without a covariance (paper 5.1: 0.2 m)");
  v->Double("default_bearing_sigma_rad", &o->default_bearing_sigma_rad, R::Above(0),
            "bearing noise of a feature without a covariance (paper 5.1: 2 degrees)", deg);
  v->Bool("use_feature_covariance", &o->use_feature_covariance,
          "a feature's own covariance when it carries one");
  v->Double("min_range_sigma_m", &o->min_range_sigma_m, R::AtLeast(0),
            "floor of a feature's own range sigma");
  v->Double("min_bearing_sigma_rad", &o->min_bearing_sigma_rad, R::AtLeast(0),
            "floor of a feature's own bearing sigma", deg);
  v->Double("min_range_m", &o->min_range_m, R::AtLeast(0), "nearer features are rejected");
  v->Double("max_range_m", &o->max_range_m, R::Above(0),
            "farther features are rejected; the range of 'in view' (paper 5.1: 30 m)");
  v->Double("field_of_view_rad", &o->field_of_view_rad, R::AboveUpTo(0, 360),
            "the laser's field of view, centred ahead", deg);
  v->Double("field_of_view_start_rad", &o->field_of_view_start_rad, R::Between(-360, 360),
            "an asymmetric view from this bearing CCW (with _end; both 0: centred)", deg);
  v->Double("field_of_view_end_rad", &o->field_of_view_end_rad, R::Between(-360, 360),
            "...to this bearing (> start, at most 360 degrees after it)", deg);
  v->Double("detection_range_m", &o->detection_range_m, R::AtLeast(0),
            "range up to which a person-sized object gives a feature (0: max_range_m)");
  v->Double("edge_of_view_sigma_m", &o->edge_of_view_sigma_m, R::AtLeast(0),
            "added sigma of a feature cut by the edge of the view (0: off)");
}

// The motion models: odometry noise, heading drift, movers.
void VisitMotionOptions(OptionVisitor* v, EstimatorOptions* o) {
  using R = OptionRange;
  v->BeginGroup("odometry_noise");
  VisitOdometryNoiseOptions(v, &o->odometry_noise);
  v->EndGroup();
  v->Double("heading_drift_sigma_rad_per_m", &o->heading_drift_sigma_rad_per_m, R::AtLeast(0),
            "prior sigma of the odometry's heading drift state b (0: no drift state)");
  v->Double("heading_drift_walk_var_per_m", &o->heading_drift_walk_var_per_m, R::AtLeast(0),
            "random walk of b [rad^2/m^2] per metre travelled");
  v->Bool("first_estimate_jacobians", &o->first_estimate_jacobians,
          "Jacobians at the first estimates (predicted pose, landmark's first position): no "
          "heading information from the filter's own landmarks");
  v->Double("mover_acceleration_sigma_mps2", &o->mover_acceleration_sigma_mps2, R::AtLeast(0),
            "process noise sigma_Q (eq. 8) of MOVING objects");
  v->Double("undecided_acceleration_sigma_mps2", &o->undecided_acceleration_sigma_mps2,
            R::AtLeast(0), "process noise sigma_Q (eq. 8) of UNDECIDED objects");
  v->BeginGroup("people");
  VisitPeopleOptions(v, &o->people);
  v->EndGroup();
  v->Double("new_object_velocity_sigma_mps", &o->new_object_velocity_sigma_mps, R::Above(0),
            "prior sigma of a new object's velocity");
  v->Double("manoeuvre_velocity_sigma_mps", &o->manoeuvre_velocity_sigma_mps, R::AtLeast(0),
            "velocity jump of a MOVING object that lost its measurement (0: off)");
}

// Time gaps, jumps back, extrapolation, the object cap.
void VisitRobustnessOptions(OptionVisitor* v, EstimatorOptions* o) {
  using R = OptionRange;
  const OptionUnit deg = OptionUnit::kDegrees;
  v->Double("max_time_gap_s", &o->max_time_gap_s, R::Above(0),
            "a longer time between scans inflates the uncertainty");
  v->Double("max_prediction_s", &o->max_prediction_s, R::Above(0),
            "the longest interval one prediction covers (>= max_time_gap_s)");
  v->Double("time_jump_back_restart_s", &o->time_jump_back_restart_s, R::Above(0),
            "a message older than its stream's newest by more is a jump (confirmed: start over)");
  v->Double("time_jump_forward_s", &o->time_jump_forward_s, R::Above(0),
            "a message newer than its stream's newest by more is a jump (confirmed: a gap)");
  v->Int("time_jump_confirm_messages", &o->time_jump_confirm_messages, R::Between(1, 100),
         "jumped messages in a row that make a new time base (1: every jump at once)");
  v->BeginGroup("odometry_check");
  VisitOdometryPlausibilityOptions(v, &o->odometry_check);
  v->EndGroup();
  v->Double("gap_robot_position_sigma_mps", &o->gap_robot_position_sigma_mps, R::AtLeast(0),
            "robot position sigma added per second of a time gap");
  v->Double("gap_robot_heading_sigma_radps", &o->gap_robot_heading_sigma_radps, R::AtLeast(0),
            "robot heading sigma added per second of a time gap", deg);
  v->Double("gap_mover_velocity_sigma_mps", &o->gap_mover_velocity_sigma_mps, R::AtLeast(0),
            "sigma added to every mover's velocity after a time gap");
  v->Double("extrapolation_speed_sigma_mps", &o->extrapolation_speed_sigma_mps, R::AtLeast(0),
            "speed noise of motion extrapolated past the last odometry, per second");
  v->Double("extrapolation_turn_sigma_radps", &o->extrapolation_turn_sigma_radps, R::AtLeast(0),
            "turn noise of motion extrapolated past the last odometry, per second", deg);
  v->Int("max_objects", &o->max_objects, R::Between(1, 100000),
         "the most objects held; new ones beyond are refused and counted");
  v->BeginGroup("window");
  VisitLandmarkWindowOptions(v, &o->window);
  v->EndGroup();
  v->Bool("smoother_first_sightings", &o->smoother_first_sightings,
          "SMOOTHER_INPUT also carries the sighting that started each object (tentative)");
  v->Bool("smoother_feedback", &o->smoother_feedback,
          "after each SMOOTHED_MAP the pose and static landmarks move to the smoother's estimate");
  v->Int("max_features_per_scan", &o->max_features_per_scan, R::Between(1, 1000000),
         "the most features of a scan used (the nearest); the rest dropped and counted");
}

// Algorithm 2: gates, RANSAC, updates, track management, classification.
void VisitAssociationOptions(OptionVisitor* v, EstimatorOptions* o) {
  using R = OptionRange;
  v->Double("gate_d1_chi2", &o->gate_d1_chi2, R::Above(0),
            "gate d1 of J, levels 1 and 2 (NIS, 2 dof; 9.21: 99 %)");
  v->Bool("level3", &o->level3, "the third level with gate d2");
  v->Double("gate_d2_chi2", &o->gate_d2_chi2, R::Above(0),
            "gate d2 of level 3 (> gate_d1_chi2; 13.82: 99.9 %)");
  v->Double("new_object_gate_dn_chi2", &o->new_object_gate_dn_chi2, R::Above(0),
            "gate dn: a measurement outside it for every object starts a new one");
  v->Bool("new_object_gate_skips_claimed_objects", &o->new_object_gate_skips_claimed_objects,
          "a non-person, non-MOVING object that took its own measurement this scan does not "
          "block a birth in its gate dn");
  v->Double("new_object_beside_claimed_min_separation_m",
            &o->new_object_beside_claimed_min_separation_m, R::AtLeast(0),
            "... when the two measured points are at least this far apart");
  v->Bool("new_object_beside_claimed_restarts_state",
          &o->new_object_beside_claimed_restarts_state,
          "... and the UNDECIDED object beside the birth starts its state again from its own "
          "measurement");
  v->BeginGroup("ransac");
  VisitRansacOptions(v, &o->ransac);
  v->EndGroup();
  v->Int("update_group_size", &o->update_group_size, R::Between(1, 4096),
         "observations per batch update");
  v->Int("max_static_updates_per_scan", &o->max_static_updates_per_scan, R::Between(0, 100000),
         "budget K of static-landmark updates per scan (0: none)");
  v->Int("max_mover_updates_per_scan", &o->max_mover_updates_per_scan, R::Between(0, 100000),
         "budget M of updates of objects with velocity per scan (0: none)");
  v->BeginGroup("tracks");
  VisitTrackManagementOptions(v, &o->tracks);
  v->EndGroup();
  v->BeginGroup("classifier");
  VisitMotionClassifierOptions(v, &o->classifier);
  v->EndGroup();
  v->BeginGroup("lines");
  VisitLineLandmarkOptions(v, &o->lines);
  v->EndGroup();
  v->BeginGroup("scan_alignment");
  VisitScanAlignmentOptions(v, &o->scan_alignment);
  v->EndGroup();
}

}  // namespace

void VisitEstimatorOptions(OptionVisitor* v, EstimatorOptions* o) {
  const OptionUnit deg = OptionUnit::kDegrees;
  int mode = static_cast<int>(o->mode);
  v->Choice("mode", &mode, {"ml_ransac", "static_nn", "ransac_all_pairs"},
            "ML-RANSAC, or baseline (a) plain EKF-SLAM of a static world, or (b) RANSAC over "
            "every pair");
  o->mode = static_cast<AssociationMode>(mode);
  v->DoubleList("initial_pose", {&o->initial_pose(0), &o->initial_pose(1), &o->initial_pose(2)},
                {OptionUnit::kAsIs, OptionUnit::kAsIs, deg}, "[x_m, y_m, heading_deg]",
                "the robot's pose at the first message: the map frame");
  VisitSensorOptions(v, o);
  VisitMotionOptions(v, o);
  VisitRobustnessOptions(v, o);
  VisitAssociationOptions(v, o);
}

std::string CheckEstimatorOptions(const EstimatorOptions& options) {
  EstimatorOptions o = options;
  OptionRangeCheck check;
  VisitEstimatorOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  // Conditions between options.
  if (!(o.max_range_m > o.min_range_m)) return "max_range_m must be > min_range_m";
  if (!(o.max_prediction_s >= o.max_time_gap_s)) {
    return "max_prediction_s must be >= max_time_gap_s";
  }
  if (o.tracks.confirm_window_scans > 0 &&
      o.tracks.confirm_window_scans < o.tracks.confirm_hits) {
    return "tracks_confirm_window_scans must be 0 or >= tracks_confirm_hits";
  }
  if (o.tracks.confirm_window_scans > 0 &&
      o.tracks.confirm_window_scans < o.tracks.confirm_person_hits) {
    return "tracks_confirm_window_scans must be 0 or >= tracks_confirm_person_hits";
  }
  if (o.tracks.report_window_scans <
      std::max(o.tracks.report_person_hits, o.tracks.report_other_hits)) {
    return "tracks_report_window_scans must be >= tracks_report_person_hits and "
           "tracks_report_other_hits";
  }
  if (o.level3 && !(o.gate_d2_chi2 > o.gate_d1_chi2)) {
    return "gate_d2_chi2 must be > gate_d1_chi2 (or level3 false)";
  }
  const std::string window = CheckLandmarkWindowOptions(o.window, o.max_range_m);
  if (!window.empty()) return window;
  if (o.field_of_view_start_rad != 0.0 || o.field_of_view_end_rad != 0.0) {
    if (!(o.field_of_view_end_rad > o.field_of_view_start_rad) ||
        o.field_of_view_end_rad - o.field_of_view_start_rad > 2.0 * M_PI + 1e-12) {
      return "field_of_view_end_deg must be > field_of_view_start_deg and at most 360 after it";
    }
    if (o.field_of_view_rad != 2.0 * M_PI) {
      return "give field_of_view_deg or field_of_view_start_deg / _end_deg, not both";
    }
  }
  return "";
}

std::string EstimatorOptionsTable() {
  EstimatorOptions defaults;
  OptionsMarkdownTable table;
  VisitEstimatorOptions(&table, &defaults);
  return table.Table();
}

}  // namespace slammtt
