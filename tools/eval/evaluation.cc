#include "tools/eval/evaluation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "common/angle.h"
#include "tools/eval/log_only_scene.h"
#include "tools/metrics/set_distance.h"

namespace slammtt {
namespace {

// The evaluation's visibility rule (evaluation.h): beams in a scan log, the world's flag in a
// feature log.
bool Visible(const TruthObjectSample& o, bool scan_log, int min_beams) {
  return scan_log ? o.beams_on_object >= min_beams : o.visible;
}

// Seen by the world (at least one beam) but short of the beams a feature needs.
bool FewBeams(const TruthObjectSample& o, bool scan_log, int min_beams) {
  return scan_log && o.beams_on_object >= 1 && o.beams_on_object < min_beams;
}

// A mover standing still at this scan (evaluation.h). Strictly below the threshold, so a
// threshold of 0 turns the rule off.
bool Standing(const TruthObjectSample& o, double min_moving_speed_mps) {
  return o.moving && o.velocity_mps.norm() < min_moving_speed_mps;
}

// Scores `pairs` already put into the truth frame by `anchor` (of the pair at anchor_utime).
TrajectoryResult ScoreAnchoredPairs(std::vector<PosePair> pairs, const Pose2& anchor,
                                    int64_t anchor_utime) {
  TrajectoryResult result;
  result.anchor_utime = anchor_utime;
  result.anchor = anchor;
  result.error = EvaluateTrajectory(pairs);
  result.relative_error = EvaluateRelativePoseError(pairs);
  for (const PosePair& p : pairs) result.anchored.push_back({p.utime, p.estimate});
  result.least_squares_alignment = LeastSquaresAlignment(pairs);  // of the anchored estimate
  for (PosePair& p : pairs) p.estimate = Compose(result.least_squares_alignment, p.estimate);
  result.aligned_error = EvaluateTrajectory(pairs);
  return result;
}

// Anchors `pairs` at the first one and scores them; nullopt without any pair.
std::optional<TrajectoryResult> ScorePairs(std::vector<PosePair> pairs) {
  if (pairs.empty()) return std::nullopt;
  const int64_t anchor_utime = pairs.front().utime;
  const Pose2 anchor = AnchorAtFirstPair(&pairs);
  return ScoreAnchoredPairs(std::move(pairs), anchor, anchor_utime);
}

// Truth scans paired with the estimates of exactly the same utime, each estimate put through
// `frame` (estimate frame -> truth frame) when one is given.
std::vector<PosePair> PairsAtExactTimes(const std::vector<TruthScan>& truth,
                                        const std::vector<TimedPose>& estimate,
                                        const Pose2* frame = nullptr) {
  std::map<int64_t, Pose2> by_time;
  for (const TimedPose& p : estimate) by_time[p.utime] = p.pose;
  std::vector<PosePair> pairs;
  for (const TruthScan& scan : truth) {
    const auto it = by_time.find(scan.utime);
    if (it == by_time.end()) continue;
    pairs.push_back({scan.utime, scan.robot, frame ? Compose(*frame, it->second) : it->second});
  }
  return pairs;
}

// Pairs truth scans with estimates at exactly the same utime.
std::optional<TrajectoryResult> ScoreExactTimes(const std::vector<TruthScan>& truth,
                                                const std::vector<TimedPose>& estimate) {
  return ScorePairs(PairsAtExactTimes(truth, estimate));
}

// Pairs truth scans with the odometry interpolated at their times.
std::optional<TrajectoryResult> ScoreInterpolated(const std::vector<TruthScan>& truth,
                                                  const std::vector<TimedPose>& odometry) {
  std::vector<PosePair> pairs;
  for (const TruthScan& scan : truth) {
    if (const auto pose = InterpolatePose(odometry, scan.utime)) {
      pairs.push_back({scan.utime, scan.robot, *pose});
    }
  }
  return ScorePairs(std::move(pairs));
}

// The smoother's trajectory and final map (EvaluationReport::smoothed_robot, smoothed_map);
// report->static_objects and mover_paths must be filled.
void ScoreSmoother(const EvalInput& input, const EvalOptions& options,
                   EvaluationReport* report) {
  if (input.smoothed_estimate.empty()) return;
  report->smoothed_robot = ScoreExactTimes(input.truth, input.smoothed_estimate);
  if (!report->smoothed_robot) {
    report->notes.push_back("no SMOOTHED_POSE has the utime of a GROUND_TRUTH scan: smoother "
                            "not scored");
    return;
  }
  if (input.final_smoothed_trajectory) {
    // In the frame of the live smoothed trajectory's anchor, as the map: the three figures
    // share one frame, and a final trajectory whose first keyframe moved is scored with it.
    std::vector<PosePair> pairs = PairsAtExactTimes(input.truth, *input.final_smoothed_trajectory,
                                                    &report->smoothed_robot->anchor);
    if (pairs.empty()) {
      report->notes.push_back("no keyframe of the last SMOOTHED_TRAJECTORY has the utime of a "
                              "GROUND_TRUTH scan: final smoothed trajectory not scored");
    } else {
      report->final_smoothed_trajectory = ScoreAnchoredPairs(
          std::move(pairs), report->smoothed_robot->anchor, report->smoothed_robot->anchor_utime);
    }
  }
  if (!input.final_smoothed_map) return;
  std::vector<IdentifiedPoint> landmarks;
  for (const LandmarkSample& l : *input.final_smoothed_map) {
    landmarks.push_back({l.id, TransformPoint(report->smoothed_robot->anchor, l.position_m)});
  }
  report->smoothed_map = ScoreMap(landmarks, report->static_objects, report->mover_paths,
                                  options.match_threshold_m);
}

std::string Count(int64_t n, const std::string& what) {
  return std::to_string(n) + " " + what;
}

// Which truth and which tracks one tracking score takes (EvaluationReport's three scores).
struct TrackingRule {
  bool coasting_tracks = false;  // confirmed tracks (coasting included), not reported ones
  // People: truth = visible people, standing ones included (every mover in a log that names no
  // person); output = MOVING tracks and tracks of kind PERSON of any class.
  bool people = false;
};

// A truth object this rule counts as a person (people rule).
bool CountedAsPerson(const TruthObjectSample& o, bool log_names_people) {
  return log_names_people ? o.kind == TruthKind::kPerson : o.moving;
}

// Adds one scan to the per-id counts of TrackingResult::false_mover_identities: each track of
// `tracks` (null: no TRACKS message) reported MOVING by `rule`, and whether `frame` left it a
// false positive (neither matched nor excused).
void CountFalseMovers(const TrackScan* tracks, const TrackingRule& rule,
                      const ClearMotFrame& frame, const std::set<int64_t>& excused,
                      std::map<int64_t, std::pair<int64_t, int64_t>>* moving_scans) {
  if (tracks == nullptr) return;
  std::set<int64_t> matched;
  for (const auto& [truth_id, track_id] : frame.matches) matched.insert(track_id);
  for (const TrackSample& t : tracks->tracks) {
    if (!(rule.coasting_tracks ? t.confirmed : t.reported) || t.label != ObjectLabel::kMoving) {
      continue;
    }
    auto& [scans, false_scans] = (*moving_scans)[t.id];
    ++scans;
    false_scans += matched.count(t.id) == 0 && excused.count(t.id) == 0 ? 1 : 0;
  }
}

// Scores the tracks of `input` (TRACKS span) against its truth by `rule`. `paths` and
// `classification` (either may be null) collect the pictures' track paths and the
// classification score.
TrackingResult ScoreTracking(const EvalInput& input, const Pose2& anchor, bool scan_log,
                             const EvalOptions& options, const TrackingRule& rule,
                             std::map<int64_t, TrackPath>* paths,
                             ClassificationAccumulator* classification) {
  bool log_names_people = false;
  for (const TruthScan& scan : input.truth) {
    for (const TruthObjectSample& o : scan.objects) {
      log_names_people = log_names_people || o.kind == TruthKind::kPerson;
    }
  }
  std::map<int64_t, const TrackScan*> tracks_at;
  for (const TrackScan& t : input.tracks) tracks_at[t.utime] = &t;
  const int64_t window_begin = input.tracks.front().utime;
  const int64_t window_end = input.tracks.back().utime;
  TrackingResult tracking;
  ClearMotAccumulator clear_mot(options.match_threshold_m);
  IdentityMetricsAccumulator identity(options.match_threshold_m);
  std::set<int64_t> movers_few_beams;
  std::set<int64_t> movers_standing;
  double ospa_sum = 0.0;
  double ospa_loc_sum = 0.0;
  double ospa_card_sum = 0.0;
  double gospa_sum = 0.0;
  // Per reported MOVING track id: (scans reported MOVING, scans of those a false positive).
  std::map<int64_t, std::pair<int64_t, int64_t>> moving_scans;
  for (const TruthScan& scan : input.truth) {
    if (scan.utime < window_begin || scan.utime > window_end) continue;
    const auto found = tracks_at.find(scan.utime);
    TrackingScan row;
    row.utime = scan.utime;
    row.had_tracks_message = found != tracks_at.end();
    if (!row.had_tracks_message) ++tracking.scans_without_tracks;

    std::vector<IdentifiedPoint> truth_movers;
    DontCare dont_care;
    std::vector<TruthObject> truth_objects;
    for (const TruthObjectSample& o : scan.objects) {
      const bool visible = Visible(o, scan_log, options.min_beams);
      const bool standing = Standing(o, options.min_moving_speed_mps);
      truth_objects.push_back({o.id, o.position_m,
                               o.moving ? ObjectLabel::kMoving : ObjectLabel::kStatic, visible,
                               standing});
      if (rule.people ? !CountedAsPerson(o, log_names_people) : !o.moving) continue;
      if (!visible) {
        dont_care.positions.push_back(o.position_m);
        ++tracking.mover_scans_invisible;
        if (FewBeams(o, scan_log, options.min_beams)) {
          ++row.num_few_beams;
          movers_few_beams.insert(o.id);
        }
      } else if (standing && !rule.people) {
        dont_care.objects.push_back({o.id, o.position_m});
        ++row.num_standing;
        movers_standing.insert(o.id);
      } else {
        truth_movers.push_back({o.id, o.position_m});
      }
    }
    tracking.mover_scans_few_beams += row.num_few_beams;
    tracking.mover_scans_standing += row.num_standing;
    std::vector<IdentifiedPoint> hypotheses;
    std::vector<LabelledTrack> labelled;
    if (row.had_tracks_message) {
      for (const TrackSample& t : found->second->tracks) {
        if (!(rule.coasting_tracks ? t.confirmed : t.reported)) continue;
        const Eigen::Vector2d p = TransformPoint(anchor, t.position_m);
        labelled.push_back({t.id, p, t.label});
        const bool counted = t.label == ObjectLabel::kMoving || (rule.people && t.person);
        if (!counted) continue;
        hypotheses.push_back({t.id, p});
        if (paths == nullptr) continue;
        TrackPath& path = (*paths)[t.id];
        path.id = t.id;
        path.points.push_back(p);
      }
    }
    const ClearMotFrame frame = clear_mot.AddFrame(truth_movers, hypotheses, dont_care);
    for (const IdentifiedPoint& p : truth_movers) row.truth_ids.push_back(p.id);
    row.matches = frame.matches;
    if (classification != nullptr) classification->AddScan(scan.utime, truth_objects, labelled);
    for (const IdentitySwitch& e : frame.id_switches) {
      tracking.identity_switches.push_back({scan.utime, e});
    }
    for (const Fragmentation& e : frame.fragmentations) {
      // Every AddFrame call has its row in tracking.scans, in order: the frame index is the row.
      const size_t since = static_cast<size_t>(e.untracked_since_frame);
      tracking.fragmentations.push_back(
          {scan.utime, since < tracking.scans.size() ? tracking.scans[since].utime : scan.utime,
           e});
    }

    const std::set<int64_t> excused(frame.dont_care_hypotheses.begin(),
                                    frame.dont_care_hypotheses.end());
    CountFalseMovers(row.had_tracks_message ? found->second : nullptr, rule, frame, excused,
                     &moving_scans);
    PointSet truth_points;
    PointSet track_points;
    std::vector<IdentifiedPoint> scored_hypotheses;
    for (const IdentifiedPoint& p : truth_movers) truth_points.push_back(p.position_m);
    for (const IdentifiedPoint& h : hypotheses) {
      if (excused.count(h.id) != 0) continue;
      track_points.push_back(h.position_m);
      scored_hypotheses.push_back(h);
    }
    identity.AddFrame(truth_movers, scored_hypotheses);
    const OspaResult ospa =
        Ospa(truth_points, track_points, options.ospa_cutoff_m, options.ospa_order);
    const GospaResult gospa = Gospa(truth_points, track_points, options.ospa_cutoff_m,
                                    options.ospa_order, options.gospa_alpha);
    row.num_truth = frame.num_truth;
    row.num_tracks = frame.num_hypotheses;
    row.num_matches = frame.num_matches;
    row.num_dont_care = frame.num_dont_care;
    row.ospa_m = ospa.distance_m;
    row.gospa_m = gospa.distance_m;
    ospa_sum += ospa.distance_m;
    ospa_loc_sum += ospa.localisation_m;
    ospa_card_sum += ospa.cardinality_m;
    gospa_sum += gospa.distance_m;
    tracking.ospa_max_m = std::max(tracking.ospa_max_m, ospa.distance_m);
    tracking.gospa_max_m = std::max(tracking.gospa_max_m, gospa.distance_m);
    tracking.gospa_missed += gospa.num_missed;
    tracking.gospa_false += gospa.num_false;
    tracking.scans.push_back(row);
  }
  if (tracking.scans.empty()) return tracking;
  const double n = static_cast<double>(tracking.scans.size());
  tracking.ospa_mean_m = ospa_sum / n;
  tracking.ospa_localisation_mean_m = ospa_loc_sum / n;
  tracking.ospa_cardinality_mean_m = ospa_card_sum / n;
  tracking.gospa_mean_m = gospa_sum / n;
  tracking.clear_mot = clear_mot.Summary();
  tracking.identity = identity.Scores();
  tracking.movers_few_beams = static_cast<int64_t>(movers_few_beams.size());
  tracking.movers_standing = static_cast<int64_t>(movers_standing.size());
  for (const auto& [id, counts] : moving_scans) {
    if (2 * counts.second <= counts.first) continue;
    ++tracking.false_mover_identities;
    tracking.false_mover_ids.push_back(id);
  }
  const double minutes = static_cast<double>(window_end - window_begin) * 1e-6 / 60.0;
  tracking.false_movers_per_minute =
      minutes > 0.0 ? static_cast<double>(tracking.false_mover_identities) / minutes : 0.0;
  return tracking;
}

// The final map's lines in the truth frame, scored against the true surfaces; the point
// landmarks on walls. Nothing when the log has neither lines nor surfaces.
void ScoreLines(const EvalInput& input, const Pose2& anchor, EvaluationReport* report) {
  if (input.final_map_lines.empty() && input.static_segments.empty()) return;
  for (const LineLandmarkSample& l : input.final_map_lines) {
    EstimatedLine e;
    e.id = l.id;
    // x' = R x + t: alpha' = alpha + theta, rho' = rho + t . n(alpha').
    const double alpha = l.line(1) + anchor.heading_rad;
    e.line = Eigen::Vector2d(l.line(0) + anchor.x_m * std::cos(alpha) +
                                 anchor.y_m * std::sin(alpha),
                             WrapAngle(alpha));
    e.from_m = TransformPoint(anchor, l.from_m);
    e.to_m = TransformPoint(anchor, l.to_m);
    report->lines.push_back(e);
  }
  std::vector<TrueSurface> surfaces;
  for (const TruthSegment& g : input.static_segments) {
    surfaces.push_back({g.id, g.kind == TruthKind::kWall, g.from_m, g.to_m});
  }
  report->line_map = ScoreLineMap(report->lines, surfaces, kLineMatchMaxAngleDeg,
                                  kLineMatchMaxDistance_m);
  std::vector<int64_t> ids;
  std::vector<Eigen::Vector2d> points;
  for (const AnchoredLandmark& a : report->landmarks) {
    ids.push_back(a.id);
    points.push_back(a.position_m);
  }
  report->point_landmarks_on_walls = PointsOnWalls(ids, points, surfaces, kWallDistance_m);
}

}  // namespace

void VisitEvalOptions(OptionVisitor* v, EvalOptions* o) {
  using R = OptionRange;
  v->Double("match_threshold_m", &o->match_threshold_m, R::Above(0),
            "CLEAR-MOT, map and classification match distance");
  v->Double("ospa_cutoff_m", &o->ospa_cutoff_m, R::Above(0), "`c` of OSPA and GOSPA");
  v->Double("ospa_order", &o->ospa_order, R::AtLeast(1), "`p` of OSPA and GOSPA");
  v->Double("gospa_alpha", &o->gospa_alpha, R::AboveUpTo(0, 2), "`alpha` of GOSPA");
  v->Int("min_beams", &o->min_beams, R::Between(1, kMaxMinBeams),
         "in a log with `LASER_SCAN`, visible = `beams_on_object >= min_beams` (without this "
         "key: `segmenter.min_points` when the file sets it)");
  v->Double("min_moving_speed_mps", &o->min_moving_speed_mps,
            R::Between(0, kMaxMinMovingSpeedMps),
            "a mover slower than this stands still (\"Movers standing still\"); 0 turns the "
            "rule off");
}

std::string CheckEvalOptions(const EvalOptions& options) {
  EvalOptions o = options;
  OptionRangeCheck check;
  VisitEvalOptions(&check, &o);
  if (!check.problem().empty()) return check.problem();
  if (!std::isfinite(o.sensor_forward_m) || !std::isfinite(o.sensor_left_m)) {
    return "the sensor mount must be finite";
  }
  return "";
}

std::string EvalOptionsTable() {
  EvalOptions defaults;
  OptionsMarkdownTable table;
  VisitEvalOptions(&table, &defaults);
  return table.Table();
}

EvaluationReport Evaluate(const EvalInput& input, const EvalOptions& options) {
  const std::string problem = CheckEvalOptions(options);
  if (!problem.empty()) throw std::invalid_argument("evaluation options: " + problem);
  EvaluationReport report;
  report.options = options;
  report.source = input.source;
  report.scan_log = input.laser_scans > 0;
  const bool scan_log = report.scan_log;
  report.truth_scans = static_cast<int64_t>(input.truth.size());
  for (const auto& [key, n] : input.rejected) {
    if (n > 0) {
      report.notes.push_back("rejected " + Count(n, key) +
                             " messages (undecodable, non-finite, unknown class, negative beam "
                             "count or repeated utime)");
    }
  }
  if (input.snapshot) {
    ScanPicture picture;
    picture.scan = *input.snapshot;
    for (const TruthScan& scan : input.truth) {
      if (scan.utime != picture.scan.utime) continue;
      const Pose2 mount = options.sensor_mount_given || !input.laser_mount
                              ? Pose2{options.sensor_forward_m, options.sensor_left_m, 0.0}
                              : *input.laser_mount;
      picture.sensor_pose = Compose(scan.robot, mount);
      picture.objects = scan.objects;
      picture.legs = scan.legs;
    }
    report.scan_picture = std::move(picture);
  }
  if (input.truth.empty()) {
    report.notes.push_back("no GROUND_TRUTH in the log: nothing can be scored");
    FillLogOnlyScene(input, &report);
    return report;
  }
  report.static_segments = input.static_segments;
  report.first_utime = input.truth.front().utime;
  report.last_utime = input.truth.back().utime;

  // Truth for the pictures and the map score.
  std::map<int64_t, std::vector<Eigen::Vector2d>> mover_paths;
  std::map<int64_t, Eigen::Vector2d> static_last_seen;
  std::map<int64_t, Eigen::Vector2d> static_any;
  std::map<int64_t, bool> ever_visible;     // by the evaluation's rule, per object
  std::map<int64_t, bool> ever_few_beams;   // seen by the world with too few beams
  std::map<int64_t, bool> is_mover;
  for (const TruthScan& scan : input.truth) {
    report.truth_trajectory.push_back({scan.utime, scan.robot});
    for (const TruthObjectSample& o : scan.objects) {
      const bool visible = Visible(o, scan_log, options.min_beams);
      ever_visible[o.id] = ever_visible[o.id] || visible;
      ever_few_beams[o.id] = ever_few_beams[o.id] || FewBeams(o, scan_log, options.min_beams);
      is_mover[o.id] = o.moving;
      if (o.moving) {
        mover_paths[o.id].push_back(o.position_m);
      } else {
        static_any[o.id] = o.position_m;
        if (visible) static_last_seen[o.id] = o.position_m;
      }
    }
  }
  for (const auto& [id, few] : ever_few_beams) {
    if (!few || ever_visible.at(id)) continue;
    ++(is_mover.at(id) ? report.movers_few_beams_only : report.statics_few_beams_only);
  }
  for (const auto& [id, path] : mover_paths) report.mover_paths.push_back(path);
  for (const auto& [id, p] : static_any) {
    if (static_last_seen.count(id) != 0) {
      report.static_objects.push_back({id, static_last_seen.at(id)});
    } else {
      report.unseen_static_objects.push_back({id, p});
    }
  }

  // Robot.
  if (input.odometry.empty()) {
    report.notes.push_back("no ODOMETRY in the log: no dead-reckoning comparison");
  } else {
    report.odometry = ScoreInterpolated(input.truth, input.odometry);
    if (!report.odometry) {
      report.notes.push_back("ODOMETRY does not cover any GROUND_TRUTH time");
    }
  }
  if (input.estimate.empty()) {
    report.notes.push_back("no POSE in the log (no estimator output): robot, map, tracking and "
                           "classification not scored");
  } else {
    report.robot = ScoreExactTimes(input.truth, input.estimate);
    if (!report.robot) {
      report.notes.push_back("no POSE has the utime of a GROUND_TRUTH scan: estimator not scored");
    } else if (report.robot->error.count < report.truth_scans) {
      report.notes.push_back(Count(report.truth_scans - report.robot->error.count,
                                   "GROUND_TRUTH scans have no POSE of the same utime"));
    }
  }
  ScoreSmoother(input, options, &report);
  if (!report.robot) return report;
  const Pose2 anchor = report.robot->anchor;

  // Map.
  if (!input.final_map) {
    report.notes.push_back("no MAP in the log: map not scored");
  } else {
    std::vector<IdentifiedPoint> landmarks;
    for (const LandmarkSample& l : *input.final_map) {
      landmarks.push_back({l.id, TransformPoint(anchor, l.position_m)});
    }
    report.map = ScoreMap(landmarks, report.static_objects, report.mover_paths,
                          options.match_threshold_m);
    std::set<int64_t> matched;
    for (const auto& [landmark, truth] : report.map->matches) matched.insert(landmark);
    const std::set<int64_t> movers(report.map->mover_landmarks.begin(),
                                   report.map->mover_landmarks.end());
    for (const LandmarkSample& l : *input.final_map) {
      AnchoredLandmark a;
      a.id = l.id;
      a.position_m = TransformPoint(anchor, l.position_m);
      a.covariance = RotateCovariance(anchor, l.covariance);
      a.kind = matched.count(l.id) != 0  ? AnchoredLandmark::Kind::kStatic
               : movers.count(l.id) != 0 ? AnchoredLandmark::Kind::kMover
                                         : AnchoredLandmark::Kind::kUnexplained;
      report.landmarks.push_back(a);
    }
    ScoreLines(input, anchor, &report);
  }

  // Tracking and classification.
  if (input.tracks.empty()) {
    report.notes.push_back("no TRACKS in the log: tracking and classification not scored");
    return report;
  }
  std::map<int64_t, TrackPath> paths;
  // Classification judges every confirmed track's label (coasting ones included).
  ClassificationAccumulator classification(options.match_threshold_m);
  TrackingResult tracking = ScoreTracking(input, anchor, scan_log, options, TrackingRule{},
                                          &paths, nullptr);
  TrackingResult with_coasting = ScoreTracking(input, anchor, scan_log, options,
                                               TrackingRule{true, false}, nullptr,
                                               &classification);
  if (tracking.scans.empty()) {
    report.notes.push_back("no GROUND_TRUTH scan within the time span of TRACKS");
    return report;
  }
  if (tracking.scans_without_tracks > 0) {
    report.notes.push_back(Count(tracking.scans_without_tracks,
                                 "GROUND_TRUTH scans within the TRACKS span have no TRACKS of "
                                 "the same utime (scored as an empty output)"));
  }
  if (!tracking.clear_mot.mota) {
    report.notes.push_back("no visible mover in motion in any scored scan: MOTA undefined");
  }
  report.tracking = tracking;
  report.tracking_with_coasting = std::move(with_coasting);
  report.people_tracking =
      ScoreTracking(input, anchor, scan_log, options, TrackingRule{false, true}, nullptr,
                    nullptr);
  report.classification = classification.Summary();
  for (auto& [id, path] : paths) report.track_paths.push_back(std::move(path));
  return report;
}

}  // namespace slammtt
