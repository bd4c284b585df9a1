#include "tools/eval/report_json.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/utime.h"

namespace slammtt {
namespace {

using nlohmann::json;

template <class T>
json OrNull(const std::optional<T>& value) {
  return value ? json(*value) : json(nullptr);
}

const char* LabelName(ObjectLabel label) {
  switch (label) {
    case ObjectLabel::kStatic:
      return "static";
    case ObjectLabel::kMoving:
      return "moving";
    case ObjectLabel::kUndecided:
      return "undecided";
  }
  return "undecided";
}

json TrajectoryJson(const TrajectoryResult& t) {
  json per_scan = {{"utime", t.error.utime},
                   {"position_error_m", t.error.position_error_m},
                   {"heading_error_rad", t.error.heading_error_rad}};
  return {{"anchor", {{"utime", t.anchor_utime},
                      {"x_m", t.anchor.x_m},
                      {"y_m", t.anchor.y_m},
                      {"heading_rad", t.anchor.heading_rad}}},
          {"scans", t.error.count},
          {"ate_rmse_m", t.error.rmse_m},
          {"ate_mean_m", t.error.mean_m},
          {"ate_max_m", t.error.max_m},
          {"ate_max_utime", t.error.max_utime},
          {"final_position_error_m", t.error.final_position_error_m},
          {"final_heading_error_rad", t.error.final_heading_error_rad},
          {"heading_rmse_rad", t.error.heading_rmse_rad},
          {"aligned", {{"ate_rmse_m", t.aligned_error.rmse_m},
                       {"ate_mean_m", t.aligned_error.mean_m},
                       {"ate_max_m", t.aligned_error.max_m}}},
          {"rpe", {{"pairs", t.relative_error.count},
                   {"translation_rmse_m", t.relative_error.translation_rmse_m},
                   {"translation_mean_m", t.relative_error.translation_mean_m},
                   {"translation_max_m", t.relative_error.translation_max_m},
                   {"rotation_rmse_rad", t.relative_error.rotation_rmse_rad}}},
          {"per_scan", per_scan}};
}

std::string Fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

// The value with its unit, or "n/a" without one.
template <class T>
std::string FixedOr(const std::optional<T>& value, int decimals, const std::string& unit = "") {
  return value ? Fixed(static_cast<double>(*value), decimals) + unit : std::string("n/a");
}

// The detail of one tracking score.
json TrackingDetail(const TrackingResult& t) {
  const ClearMotSummary& c = t.clear_mot;
  json per_scan = {{"utime", json::array()},       {"ospa_m", json::array()},
                   {"gospa_m", json::array()},     {"truth", json::array()},
                   {"tracks", json::array()},      {"matches", json::array()},
                   {"dont_care", json::array()},   {"few_beams", json::array()},
                   {"standing", json::array()}};
  for (const TrackingScan& s : t.scans) {
    per_scan["utime"].push_back(s.utime);
    per_scan["ospa_m"].push_back(s.ospa_m);
    per_scan["gospa_m"].push_back(s.gospa_m);
    per_scan["truth"].push_back(s.num_truth);
    per_scan["tracks"].push_back(s.num_tracks);
    per_scan["matches"].push_back(s.num_matches);
    per_scan["dont_care"].push_back(s.num_dont_care);
    per_scan["few_beams"].push_back(s.num_few_beams);
    per_scan["standing"].push_back(s.num_standing);
  }
  json switches = json::array();
  for (const IdentitySwitchEvent& e : t.identity_switches) {
    switches.push_back({{"utime", e.utime},
                        {"truth_id", e.what.truth_id},
                        {"previous_track_id", e.what.previous_hypothesis_id},
                        {"new_track_id", e.what.new_hypothesis_id}});
  }
  json fragmentations = json::array();
  for (const FragmentationEvent& e : t.fragmentations) {
    fragmentations.push_back({{"utime", e.utime},
                              {"untracked_since_utime", e.untracked_since_utime},
                              {"truth_id", e.what.truth_id},
                              {"previous_track_id", e.what.previous_hypothesis_id},
                              {"new_track_id", e.what.new_hypothesis_id}});
  }
  return {
      {"scans", static_cast<int64_t>(t.scans.size())},
      {"scans_without_tracks", t.scans_without_tracks},
      {"false_mover_identities", t.false_mover_identities},
      {"false_mover_ids", t.false_mover_ids},
      {"ospa", {{"mean_m", t.ospa_mean_m},
                {"max_m", t.ospa_max_m},
                {"localisation_mean_m", t.ospa_localisation_mean_m},
                {"cardinality_mean_m", t.ospa_cardinality_mean_m}}},
      {"gospa", {{"mean_m", t.gospa_mean_m},
                 {"max_m", t.gospa_max_m},
                 {"missed", t.gospa_missed},
                 {"false", t.gospa_false}}},
      {"clear_mot", {{"truth", c.num_truth},
                     {"matches", c.num_matches},
                     {"misses", c.num_misses},
                     {"false_positives", c.num_false_positives},
                     {"id_switches", c.num_id_switches},
                     {"fragmentations", c.num_fragmentations},
                     {"dont_care", c.num_dont_care},
                     {"mota", OrNull(c.mota)},
                     {"motp_m", OrNull(c.motp_m)}}},
      {"identity", {{"idf1", OrNull(t.identity.idf1)},
                    {"id_precision", OrNull(t.identity.id_precision)},
                    {"id_recall", OrNull(t.identity.id_recall)},
                    {"id_true_positives", t.identity.id_true_positives},
                    {"id_false_positives", t.identity.id_false_positives},
                    {"id_false_negatives", t.identity.id_false_negatives},
                    {"hota", OrNull(t.identity.hota)},
                    {"det_a", OrNull(t.identity.det_a)},
                    {"ass_a", OrNull(t.identity.ass_a)},
                    {"loc_a", OrNull(t.identity.loc_a)}}},
      {"dont_care", {{"tracks_on_standing_movers", c.num_dont_care_objects},
                     {"tracks_near_invisible_movers", c.num_dont_care_positions},
                     {"mover_scans_invisible", t.mover_scans_invisible},
                     {"mover_scans_few_beams", t.mover_scans_few_beams},
                     {"movers_few_beams", t.movers_few_beams},
                     {"mover_scans_standing", t.mover_scans_standing},
                     {"movers_standing", t.movers_standing}}},
      {"identity_switch_events", switches},
      {"fragmentation_events", fragmentations},
      {"per_scan", per_scan}};
}

// detail.map.lines: the line landmarks against the true surfaces (docs/evaluation.md).
json LineMapJson(const EvaluationReport& report) {
  const LineMapScore& l = *report.line_map;
  json matches = json::array();
  for (const LineMatch& m : l.matches) {
    matches.push_back({{"line_id", m.line_id},
                       {"surface_id", m.surface_id},
                       {"wall", m.wall},
                       {"angle_error_deg", m.angle_error_deg},
                       {"distance_error_m", m.distance_error_m}});
  }
  return {{"lines", l.num_lines},
          {"matched", static_cast<int64_t>(l.matches.size())},
          {"unmatched_line_ids", l.unmatched_ids},
          {"angle_error_deg",
           {{"median", l.angle_error_median_deg},
            {"p95", l.angle_error_p95_deg},
            {"max", l.angle_error_max_deg}}},
          {"distance_error_m",
           {{"median", l.distance_error_median_m},
            {"p95", l.distance_error_p95_m},
            {"max", l.distance_error_max_m}}},
          {"point_landmarks_on_walls",
           static_cast<int64_t>(report.point_landmarks_on_walls.size())},
          {"point_landmark_on_wall_ids", report.point_landmarks_on_walls},
          {"matches", matches}};
}

}  // namespace

const std::vector<std::string>& TopLevelMetricKeys() {
  static const std::vector<std::string> keys = {
      "ate_rmse_m",      "odometry_ate_rmse_m",  "ospa_mean_m",     "gospa_mean_m",
      "mota",            "motp_m",               "id_switches",     "fragmentations",
      "idf1",            "hota",                 "mota_with_coasting",
      "id_switches_with_coasting",               "people_mota",     "people_id_switches",
      "non_person_movers_per_minute",
      "movers_in_static_map", "landmark_rmse_m", "static_recall",   "classification_accuracy",
      "smoothed_ate_rmse_m",  "smoothed_landmark_rmse_m", "final_smoothed_ate_rmse_m"};
  return keys;
}

std::vector<ReportWarning> ReportWarnings(const EvaluationReport& report,
                                          const std::string& log_problem) {
  std::vector<ReportWarning> warnings;
  if (!log_problem.empty()) warnings.push_back({"log_truncated", log_problem, false});
  const auto too_few = [](int64_t scored, int64_t of) {
    return of > 0 && static_cast<double>(scored) < kMinScoredFraction * static_cast<double>(of);
  };
  if (report.robot && too_few(report.robot->error.count, report.truth_scans)) {
    warnings.push_back(
        {"pose_coverage",
         "the ATE is computed from " + std::to_string(report.robot->error.count) + " of " +
             std::to_string(report.truth_scans) +
             " ground-truth scans (a POSE of the same utime; fewer than half): not a headline",
         true});
  }
  if (report.tracking) {
    const int64_t scans = static_cast<int64_t>(report.tracking->scans.size());
    const int64_t with_tracks = scans - report.tracking->scans_without_tracks;
    if (too_few(with_tracks, scans)) {
      warnings.push_back({"tracks_coverage",
                          "only " + std::to_string(with_tracks) + " of " +
                              std::to_string(scans) +
                              " scored ground-truth scans have a TRACKS of the same utime "
                              "(fewer than half): tracking figures are not a headline",
                          true});
    }
  }
  return warnings;
}

std::string ReportJsonText(const nlohmann::json& report) {
  return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

json ReportToJson(const EvalInput& input, const EvaluationReport& report,
                  const std::vector<ReportWarning>& warnings) {
  json j;
  j["ate_rmse_m"] = report.robot ? json(report.robot->error.rmse_m) : json(nullptr);
  j["odometry_ate_rmse_m"] = report.odometry ? json(report.odometry->error.rmse_m) : json(nullptr);
  j["ospa_mean_m"] = report.tracking ? json(report.tracking->ospa_mean_m) : json(nullptr);
  j["gospa_mean_m"] = report.tracking ? json(report.tracking->gospa_mean_m) : json(nullptr);
  j["mota"] = report.tracking ? OrNull(report.tracking->clear_mot.mota) : json(nullptr);
  j["motp_m"] = report.tracking ? OrNull(report.tracking->clear_mot.motp_m) : json(nullptr);
  j["id_switches"] =
      report.tracking ? json(report.tracking->clear_mot.num_id_switches) : json(nullptr);
  j["idf1"] = report.tracking ? OrNull(report.tracking->identity.idf1) : json(nullptr);
  j["hota"] = report.tracking ? OrNull(report.tracking->identity.hota) : json(nullptr);
  j["fragmentations"] =
      report.tracking ? json(report.tracking->clear_mot.num_fragmentations) : json(nullptr);
  const auto& coasting = report.tracking_with_coasting;
  j["mota_with_coasting"] = coasting ? OrNull(coasting->clear_mot.mota) : json(nullptr);
  j["id_switches_with_coasting"] =
      coasting ? json(coasting->clear_mot.num_id_switches) : json(nullptr);
  const auto& people = report.people_tracking;
  j["people_mota"] = people ? OrNull(people->clear_mot.mota) : json(nullptr);
  j["people_id_switches"] = people ? json(people->clear_mot.num_id_switches) : json(nullptr);
  j["non_person_movers_per_minute"] =
      people ? json(people->false_movers_per_minute) : json(nullptr);
  j["movers_in_static_map"] =
      report.map ? json(report.map->num_movers_in_static_map) : json(nullptr);
  j["landmark_rmse_m"] = report.map ? OrNull(report.map->landmark_rmse_m) : json(nullptr);
  j["static_recall"] = report.map ? OrNull(report.map->static_recall) : json(nullptr);
  j["classification_accuracy"] =
      report.classification ? OrNull(report.classification->accuracy) : json(nullptr);
  j["smoothed_ate_rmse_m"] =
      report.smoothed_robot ? json(report.smoothed_robot->error.rmse_m) : json(nullptr);
  j["smoothed_landmark_rmse_m"] =
      report.smoothed_map ? OrNull(report.smoothed_map->landmark_rmse_m) : json(nullptr);
  j["final_smoothed_ate_rmse_m"] = report.final_smoothed_trajectory
                                       ? json(report.final_smoothed_trajectory->error.rmse_m)
                                       : json(nullptr);

  json detail;
  json channels;
  for (const auto& [key, n] : input.accepted) channels[key]["accepted"] = n;
  for (const auto& [key, n] : input.rejected) channels[key]["rejected"] = n;
  detail["input"] = {{"log", report.source},
                     {"ground_truth_scans", report.truth_scans},
                     {"laser_scans", input.laser_scans},
                     {"first_utime", report.first_utime},
                     {"last_utime", report.last_utime},
                     {"messages", channels}};
  detail["options"] = {{"match_threshold_m", report.options.match_threshold_m},
                       {"ospa_cutoff_m", report.options.ospa_cutoff_m},
                       {"ospa_order", report.options.ospa_order},
                       {"gospa_alpha", report.options.gospa_alpha},
                       {"min_beams", report.options.min_beams},
                       {"min_moving_speed_mps", report.options.min_moving_speed_mps},
                       {"visibility", report.scan_log
                                          ? "beams_on_object >= min_beams (log with LASER_SCAN)"
                                          : "the world's visible flag (log without LASER_SCAN)"}};
  detail["robot"] = report.robot ? TrajectoryJson(*report.robot) : json(nullptr);
  detail["odometry"] = report.odometry ? TrajectoryJson(*report.odometry) : json(nullptr);
  // The smoother's parts only when the log has its outputs.
  if (report.smoothed_robot) detail["smoothed_robot"] = TrajectoryJson(*report.smoothed_robot);
  if (report.final_smoothed_trajectory) {
    detail["final_smoothed_trajectory"] = TrajectoryJson(*report.final_smoothed_trajectory);
    detail["final_smoothed_trajectory"]["trajectory_utime"] =
        input.final_smoothed_trajectory_utime;
  }
  if (report.smoothed_map) {
    const MapScore& m = *report.smoothed_map;
    detail["smoothed_map"] = {{"final_map_utime", input.final_smoothed_map_utime},
                              {"landmarks", m.num_landmarks},
                              {"matched", m.num_matched},
                              {"static_recall", OrNull(m.static_recall)},
                              {"landmark_rmse_m", OrNull(m.landmark_rmse_m)},
                              {"landmark_max_error_m", m.landmark_max_error_m},
                              {"movers_in_static_map", m.num_movers_in_static_map}};
  }
  if (report.map) {
    const MapScore& m = *report.map;
    json matches = json::array();
    for (const auto& [landmark, truth] : m.matches) {
      matches.push_back({{"landmark_id", landmark}, {"truth_id", truth}});
    }
    detail["map"] = {{"final_map_utime", input.final_map_utime},
                     {"landmarks", m.num_landmarks},
                     {"static_objects_ever_visible", m.num_static_truth},
                     {"static_objects_never_visible",
                      static_cast<int64_t>(report.unseen_static_objects.size())},
                     {"static_objects_few_beams_only", report.statics_few_beams_only},
                     {"matched", m.num_matched},
                     {"static_recall", OrNull(m.static_recall)},
                     {"landmark_rmse_m", OrNull(m.landmark_rmse_m)},
                     {"landmark_max_error_m", m.landmark_max_error_m},
                     {"movers_in_static_map", m.num_movers_in_static_map},
                     {"mover_landmark_ids", m.mover_landmarks},
                     {"unexplained_landmark_ids", m.unexplained_landmarks},
                     {"matches", matches}};
    if (report.line_map) detail["map"]["lines"] = LineMapJson(report);
  } else {
    detail["map"] = nullptr;
  }
  detail["tracking"] = report.tracking ? TrackingDetail(*report.tracking) : json(nullptr);
  detail["tracking_with_coasting"] = report.tracking_with_coasting
                                         ? TrackingDetail(*report.tracking_with_coasting)
                                         : json(nullptr);
  detail["people_tracking"] =
      report.people_tracking ? TrackingDetail(*report.people_tracking) : json(nullptr);
  if (report.classification) {
    const ClassificationSummary& s = *report.classification;
    json objects = json::array();
    for (const ObjectClassification& o : s.objects) {
      objects.push_back({{"id", o.id},
                         {"true_class", LabelName(o.true_class)},
                         {"first_visible_utime", o.first_visible_utime},
                         {"matched_scans", o.num_matched_scans},
                         {"final_label", o.final_label ? json(LabelName(*o.final_label))
                                                       : json("untracked")},
                         {"delay_s", OrNull(o.delay_s)},
                         {"visible_scans_until_right", OrNull(o.visible_scans_until_right)},
                         {"correct", o.correct}});
    }
    json confusion;
    const char* rows[kNumTrueClasses] = {"static", "moving"};
    const char* cols[kNumFinalLabels] = {"static", "moving", "undecided", "untracked"};
    for (int r = 0; r < kNumTrueClasses; ++r) {
      for (int c = 0; c < kNumFinalLabels; ++c) confusion[rows[r]][cols[c]] = s.confusion[r][c];
    }
    detail["classification"] = {{"objects", objects},
                                {"movers_seen_only_standing", s.movers_seen_only_standing},
                                {"movers_few_beams_only", report.movers_few_beams_only},
                                {"confusion_true_by_final", confusion},
                                {"accuracy", OrNull(s.accuracy)},
                                {"accuracy_of_tracked", OrNull(s.accuracy_of_tracked)},
                                {"mean_delay_s", OrNull(s.mean_delay_s)},
                                {"max_delay_s", OrNull(s.max_delay_s)},
                                {"mean_visible_scans_until_right",
                                 OrNull(s.mean_visible_scans_until_right)}};
  } else {
    detail["classification"] = nullptr;
  }
  detail["notes"] = report.notes;
  j["detail"] = detail;
  json listed = json::array();
  for (const ReportWarning& w : warnings) {
    listed.push_back({{"code", w.code}, {"message", w.message}});
    if (!w.withholds) continue;
    if (w.code == "pose_coverage") j["ate_rmse_m"] = nullptr;
    if (w.code == "tracks_coverage") {
      for (const char* key : {"ospa_mean_m", "gospa_mean_m", "mota", "motp_m", "id_switches",
                              "fragmentations", "idf1", "hota", "mota_with_coasting",
                              "id_switches_with_coasting", "people_mota",
                              "people_id_switches", "non_person_movers_per_minute"}) {
        j[key] = nullptr;
      }
    }
  }
  j["warnings"] = listed;
  return j;
}

std::string ReportSummaryText(const EvaluationReport& report,
                              const std::vector<ReportWarning>& warnings) {
  std::ostringstream out;
  const double span_s = SecondsBetween(report.last_utime, report.first_utime);
  out << "evaluation of " << report.source << ": " << report.truth_scans
      << " ground-truth scans, " << Fixed(span_s, 1) << " s\n";
  out << "  robot:          ";
  if (report.robot) {
    const TrajectoryError& e = report.robot->error;
    out << "ATE RMSE " << Fixed(e.rmse_m, 3) << " m, max " << Fixed(e.max_m, 3)
        << " m, final heading error " << Fixed(e.final_heading_error_rad * 180.0 / M_PI, 2)
        << " deg";
  } else {
    out << "n/a";
  }
  out << "\n  odometry:       ";
  if (report.odometry) {
    const TrajectoryError& e = report.odometry->error;
    out << "ATE RMSE " << Fixed(e.rmse_m, 3) << " m, max " << Fixed(e.max_m, 3)
        << " m, final heading error " << Fixed(e.final_heading_error_rad * 180.0 / M_PI, 2)
        << " deg";
  } else {
    out << "n/a";
  }
  if (report.smoothed_robot) {
    const TrajectoryError& e = report.smoothed_robot->error;
    out << "\n  smoothed robot: ATE RMSE " << Fixed(e.rmse_m, 3) << " m, max " << Fixed(e.max_m, 3)
        << " m";
    if (report.smoothed_map) {
      out << "; smoothed map: landmark RMSE "
          << FixedOr(report.smoothed_map->landmark_rmse_m, 3, " m") << ", recall "
          << FixedOr(report.smoothed_map->static_recall, 3);
    }
    if (report.final_smoothed_trajectory) {
      const TrajectoryError& f = report.final_smoothed_trajectory->error;
      out << "\n  final smoothed trajectory (" << report.final_smoothed_trajectory->anchored.size()
          << " keyframes): ATE RMSE " << Fixed(f.rmse_m, 3) << " m, max " << Fixed(f.max_m, 3)
          << " m";
    }
  }
  out << "\n  map:            ";
  if (report.map) {
    const MapScore& m = *report.map;
    out << m.num_matched << " of " << m.num_static_truth << " static objects found (recall "
        << FixedOr(m.static_recall, 3) << "), landmark RMSE " << FixedOr(m.landmark_rmse_m, 3, " m")
        << ", " << m.num_movers_in_static_map << " movers in the static map, "
        << m.num_unexplained << " other landmarks";
    if (report.line_map) {
      const LineMapScore& l = *report.line_map;
      out << "\n  lines:          " << l.matches.size() << " of " << l.num_lines
          << " line landmarks on a true surface, angle error median / max "
          << Fixed(l.angle_error_median_deg, 2) << " / " << Fixed(l.angle_error_max_deg, 2)
          << " deg, distance error median / max " << Fixed(l.distance_error_median_m, 3) << " / "
          << Fixed(l.distance_error_max_m, 3) << " m, " << report.point_landmarks_on_walls.size()
          << " point landmarks on walls";
    }
  } else {
    out << "n/a";
  }
  out << "\n  tracking:       ";
  if (report.tracking) {
    const TrackingResult& t = *report.tracking;
    out << "OSPA mean " << Fixed(t.ospa_mean_m, 3) << " m, GOSPA mean " << Fixed(t.gospa_mean_m, 3)
        << " m, MOTA " << FixedOr(t.clear_mot.mota, 3) << ", MOTP "
        << FixedOr(t.clear_mot.motp_m, 3, " m") << ", " << t.clear_mot.num_id_switches
        << " identity switches, " << t.clear_mot.num_fragmentations << " fragmentations, IDF1 "
        << FixedOr(t.identity.idf1, 3) << ", HOTA " << FixedOr(t.identity.hota, 3);
    out << "\n  don't care:     " << t.mover_scans_standing << " mover-scans standing still (<"
        << Fixed(report.options.min_moving_speed_mps, 2) << " m/s), " << t.mover_scans_invisible
        << " invisible";
    if (report.scan_log && report.options.min_beams > 1) {
      out << " (" << t.mover_scans_few_beams << " with 1-" << report.options.min_beams - 1
          << " beams)";
    }
    out << "; " << t.clear_mot.num_dont_care << " tracks excused";
    if (report.tracking_with_coasting) {
      const ClearMotSummary& c = report.tracking_with_coasting->clear_mot;
      out << "\n  with coasting:  MOTA " << FixedOr(c.mota, 3) << ", " << c.num_id_switches
          << " identity switches (every confirmed track, measured or not)";
    }
    if (report.people_tracking) {
      const ClearMotSummary& c = report.people_tracking->clear_mot;
      out << "\n  people:         MOTA " << FixedOr(c.mota, 3) << ", MOTP "
          << FixedOr(c.motp_m, 3, " m") << ", " << c.num_id_switches
          << " identity switches (visible people, standing ones counted); "
          << report.people_tracking->false_mover_identities << " movers that are no person ("
          << Fixed(report.people_tracking->false_movers_per_minute, 2)
          << " per minute)";
    }
  } else {
    out << "n/a";
  }
  out << "\n  classification: ";
  if (report.classification) {
    const ClassificationSummary& c = *report.classification;
    int64_t correct = 0;
    for (const ObjectClassification& o : c.objects) correct += o.correct ? 1 : 0;
    out << correct << " of " << c.objects.size() << " objects labelled right (accuracy "
        << FixedOr(c.accuracy, 3) << "), mean delay " << FixedOr(c.mean_delay_s, 2, " s") << " ("
        << FixedOr(c.mean_visible_scans_until_right, 1) << " visible scans)";
  } else {
    out << "n/a";
  }
  out << "\n";
  for (const std::string& note : report.notes) out << "  note: " << note << "\n";
  for (const ReportWarning& w : warnings) out << "  warning: " << w.message << "\n";
  return out.str();
}

}  // namespace slammtt
