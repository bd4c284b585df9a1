#include "estimator/estimator.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "common/angle.h"
#include "common/checked_options.h"
#include "common/utime.h"
#include "estimator/association.h"
#include "estimator/classification.h"
#include "estimator/hits_and_misses.h"
#include "estimator/level1.h"
#include "estimator/level3.h"
#include "estimator/line_model.h"
#include "estimator/manoeuvres.h"
#include "estimator/nearest_neighbour.h"
#include "estimator/new_objects.h"
#include "estimator/observation_predictions.h"
#include "estimator/people.h"
#include "estimator/pruning.h"
#include "estimator/ransac_level.h"
#include "estimator/reacquisition.h"
#include "estimator/scan_gating.h"
#include "estimator/state_recovery.h"
#include "estimator/track_management.h"
#include "estimator/update_budget.h"

namespace slammtt {
namespace {

// The state before the first message (and after a restart): the robot at initial_pose (its
// heading wrapped), known exactly (it defines the map frame), the heading drift at its prior.
SlamState InitialState(const EstimatorOptions& options) {
  const double drift_sigma = options.heading_drift_sigma_rad_per_m;
  Eigen::Vector3d pose = options.initial_pose;
  pose(2) = WrapAngle(pose(2));
  SlamState state(pose, Eigen::Matrix3d::Zero(), drift_sigma * drift_sigma);
  state.set_first_estimate_jacobians(options.first_estimate_jacobians);
  return state;
}

}  // namespace

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

Estimator::Estimator(const EstimatorOptions& options)
    : options_(CheckedOptions(options, &CheckEstimatorOptions, "estimator options")),
      state_(InitialState(options)),
      last_finite_pose_(state_.robot_pose()) {}

void Estimator::SetLaserGeometry(const EstimatorOptions& options) {
  EstimatorOptions next = options_;
  next.sensor = options.sensor;
  next.field_of_view_rad = options.field_of_view_rad;
  next.field_of_view_start_rad = options.field_of_view_start_rad;
  next.field_of_view_end_rad = options.field_of_view_end_rad;
  next.max_range_m = options.max_range_m;
  options_ = CheckedOptions(next, &CheckEstimatorOptions, "estimator options");
}

TimeJumpLimits Estimator::time_jump_limits() const {
  return TimeJumpLimits{options_.time_jump_back_restart_s, options_.time_jump_forward_s,
                        options_.time_jump_confirm_messages};
}

void Estimator::StartOver() {
  state_ = InitialState(options_);
  last_scan_utime_.reset();
  scan_clock_.Reset();
  odometry_clock_.Reset();
  odometry_check_.Reset();
  odometry_.Clear();
  scan_motion_.Clear();
  last_finite_pose_ = state_.robot_pose();
  last_finite_pose_covariance_ = state_.robot_covariance();
  line_candidates_.clear();
  archive_.Clear();
  pose_history_.Clear();
}

bool Estimator::AcceptTime(const char* what, int64_t utime, StreamClock* clock) {
  const std::optional<int64_t> newest = clock->newest();
  const TimeVerdict verdict = clock->Judge(utime, time_jump_limits());
  std::ostringstream text;
  text << what << " at utime " << utime;
  switch (verdict) {
    case TimeVerdict::kAccept:
      return true;
    case TimeVerdict::kLate:
      ++counters_.messages_out_of_order;
      text << " dropped: not newer than the last one (" << *newest << ")";
      Event(text.str());
      return false;
    case TimeVerdict::kJumpHeld:
      ++counters_.time_jumps_rejected;
      text << " dropped: " << SecondsBetween(utime, *newest) << " s from the newest ("
           << *newest << "), a jump (" << clock->jumped_in_a_row() << " in a row, "
           << options_.time_jump_confirm_messages << " make a new time base)";
      Event(text.str());
      return false;
    case TimeVerdict::kNewTimeBaseBack:
      ++counters_.restarts;
      text << ": " << options_.time_jump_confirm_messages << " messages in a row "
           << SecondsBetween(*newest, utime) << " s older than the newest (" << *newest
           << "), a new time base: estimation started over";
      StartOver();
      clock->Judge(utime, time_jump_limits());  // the first message of the new base
      Event(text.str());
      return true;
    case TimeVerdict::kNewTimeBaseAhead:
      text << ": " << options_.time_jump_confirm_messages << " messages in a row "
           << SecondsBetween(utime, *newest) << " s ahead of the newest (" << *newest
           << "), a new time base, taken as a time gap";
      Event(text.str());
      return true;
  }
  return false;
}

bool Estimator::AddOdometry(const OdometryReading& reading) {
  std::string problem = OdometryReadingProblem(reading, options_.odometry_check);
  if (!problem.empty()) {
    ++counters_.odometry_rejected;
    Event("odometry at utime " + std::to_string(reading.utime) + " rejected: " + problem);
    return false;
  }
  if (!AcceptTime("odometry", reading.utime, &odometry_clock_)) return false;
  const OdometryVerdict verdict = odometry_check_.Judge(
      reading, options_.odometry_check, options_.time_jump_confirm_messages, &problem);
  if (verdict == OdometryVerdict::kImplausible) {
    ++counters_.odometry_rejected;
    Event("odometry at utime " + std::to_string(reading.utime) + " rejected: " + problem);
    return false;
  }
  ++counters_.odometry_processed;
  if (verdict == OdometryVerdict::kNewFrame) {
    ++counters_.odometry_frame_jumps;
    Event("odometry at utime " + std::to_string(reading.utime) + ": " +
          std::to_string(options_.time_jump_confirm_messages) +
          " consistent readings in a row away from the last accepted one, a new odometry "
          "frame (motion across the jump extrapolated)");
    odometry_.AddInNewFrame(reading);
    return true;
  }
  odometry_.Add(reading);
  return true;
}

// What the steps of one scan hand on to each other.
struct Estimator::ScanInProgress {
  ScanInProgress(int64_t scan_utime, const ScanInterval& scan_interval,
                 const SensorMount& sensor, StepCounts* step_counts)
      : utime(scan_utime), interval(scan_interval), counts(step_counts), predicted(sensor) {}

  // The scan as the association levels see it (association.h).
  ScanAssociation association() const { return {features.measurements, may_update, utime}; }

  const int64_t utime;
  const ScanInterval interval;
  StepCounts* const counts;
  ValidatedFeatures features;          // the point measurements, off the line landmarks
  ObservationPredictions predicted;    // once per state the scan passes through
  ScanGating gating;                   // at the predicted state
  std::vector<uint8_t> may_update;     // per object: the budget of updates
  Assignment assignment{0, 0};         // measurement <-> object, level by level
  // Without odometry: the scan's static-looking features, the next scan's alignment reference.
  std::optional<AlignmentScan> alignment_scan;
  std::optional<ScanAlignment> alignment;  // its alignment with the previous one
};

namespace {

// Tells the observer (if any) that a sub-stage of the scan ended.
struct SubstageLaps {
  StepObserver* observer;
  void operator()(Substage substage) const {
    if (observer != nullptr) observer->SubstageDone(substage);
  }
};

}  // namespace

ScanResult Estimator::ProcessScan(const ScanInput& scan, std::mt19937_64* rng,
                                  StepObserver* observer) {
  ScanResult result;
  result.utime = scan.utime;
  result.counts.features = static_cast<int>(scan.features.size());
  if (!AcceptScanTime(scan.utime)) return result;
  const SubstageLaps lap{observer};
  ScanInProgress s(scan.utime, IntervalTo(scan.utime), options_.sensor, &result.counts);
  if (options_.window.radius_m > 0.0) {
    s.predicted.HoldBackReentriesBeyond(options_.max_range_m, FieldOfViewOf(options_));
  }
  s.features = TakeFeatures(scan.features, s.counts);

  // Line 2: propagate the whole state to the scan (step 1); the walls then correct the pose
  // before the points are judged (step 1b).
  PropagateState(scan, &s);
  RestoreNearbyLandmarks(&s);
  lap(Substage::kPredict);
  // Lines 3-4: individual compatibility with gate d1, the association matrix J (steps 2-3).
  GateMeasurements(&s);
  lap(Substage::kGating);
  // Lines 5-6: the first level EKF update with the pairs J settles (step 4).
  const std::vector<Candidate> ambiguous = UpdateFirstLevel(&s);
  lap(Substage::kLevel1);
  // Line 7 a-d: RANSAC over the observations J leaves to decide (step 5)...
  const RansacOutcome ransac = FindRansacConsensus(ambiguous, rng, &s);
  lap(Substage::kRansac);
  // ... e: the second level EKF update with its consensus, gate d1.
  UpdateSecondLevel(ransac, &s);
  // Line 9 (optional): the third level EKF update with gate d2 > d1 (step 6).
  UpdateThirdLevel(&s);
  lap(Substage::kLevel23);
  // Lines 11-13: prune, determine static or dynamic, initialise new tracks (steps 7-10); what
  // the scan measured of the static landmarks is kept for the smoother.
  result.static_observations = ManageTracks(&s);
  ArchiveDistantLandmarks(&s);
  FinishScan(&s);
  lap(Substage::kTrackManagement);
  ++counters_.scans_processed;
  ReportEstimate(scan.utime, &result);
  pose_history_.Record(scan.utime, state_.robot_pose());
  return result;
}

FeedbackCounts Estimator::ApplySmoothedEstimate(const SmoothedEstimate& smoothed) {
  const std::optional<Eigen::Vector3d> filter_then = pose_history_.At(smoothed.utime);
  if (!filter_then) {
    ++counters_.smoother_feedbacks_stale;
    return FeedbackCounts{};
  }
  const Eigen::Vector3d pose_now =
      CarryPoseForward(smoothed.pose, *filter_then, state_.robot_pose());
  const FeedbackCounts counts = ShiftToSmoothedEstimate(smoothed, pose_now, &state_, &archive_);
  pose_history_.KeepNewestAs(state_.robot_pose());
  ++counters_.smoother_feedbacks;
  return counts;
}

void Estimator::PropagateState(const ScanInput& scan, ScanInProgress* s) {
  s->alignment = AlignWithPreviousScan(scan, s);
  Predict(scan.utime, s->interval, s->alignment ? &*s->alignment : nullptr);
  last_scan_utime_ = scan.utime;
  UpdateLines(scan, s->counts);
  DropPointsOnLines(&s->features, s->counts);
}

void Estimator::GateMeasurements(ScanInProgress* s) {
  s->gating = GateScan(s->features.measurements, s->predicted.At(state_), options_);
  s->may_update =
      ObjectsThatMayUpdate(state_, s->gating.gated, options_.max_static_updates_per_scan,
                           options_.max_mover_updates_per_scan);
  s->assignment =
      Assignment(static_cast<int>(s->features.measurements.size()), state_.num_objects());
}

std::vector<Candidate> Estimator::UpdateFirstLevel(ScanInProgress* s) {
  if (options_.mode == AssociationMode::kStaticNearestNeighbour) {
    AssociateNearestNeighbours(s->gating.compatible, s->association(), options_, &s->predicted,
                               &state_, &s->assignment, s->counts);
    return {};
  }
  if (options_.mode != AssociationMode::kMlRansac) return {};
  return AssociateLevel1(s->gating.compatible, s->association(), options_, &s->predicted,
                         &state_, &s->assignment, s->counts);
}

RansacOutcome Estimator::FindRansacConsensus(const std::vector<Candidate>& ambiguous,
                                             std::mt19937_64* rng, ScanInProgress* s) {
  RansacOutcome ransac;  // none in the static-world baseline
  if (options_.mode != AssociationMode::kStaticNearestNeighbour) {
    ransac = RunRansacLevel(ambiguous, s->association(), options_, &s->predicted, state_,
                            s->assignment, rng);
  }
  s->counts->hypotheses = ransac.hypotheses;
  s->counts->ransac_pair_tests = ransac.pair_tests;
  counters_.hypotheses_generated += ransac.hypotheses;
  if (ransac.budget_cut) {
    s->counts->ransac_budget_cut = 1;
    ++counters_.ransac_budget_cuts;
    Event("scan at utime " + std::to_string(s->utime) + ": RANSAC stopped after " +
          std::to_string(ransac.hypotheses) + " hypotheses at ransac_max_pair_tests (" +
          std::to_string(options_.ransac.max_pair_tests) + " pair tests)");
  }
  return ransac;
}

void Estimator::UpdateSecondLevel(const RansacOutcome& ransac, ScanInProgress* s) {
  s->counts->level2_updates =
      ApplyPairs(ransac.consensus, options_.gate_d1_chi2, s->association(), options_,
                 &s->predicted, &state_, &s->assignment, s->counts);
}

void Estimator::UpdateThirdLevel(ScanInProgress* s) {
  if (options_.level3 && options_.mode != AssociationMode::kStaticNearestNeighbour) {
    GiveManoeuvringMoversAVelocityJump(s->interval.dt_s, s->association(), options_,
                                       &s->predicted, &state_, s->assignment, s->counts);
    AssociateLevel3(s->association(), options_, &s->predicted, &state_, &s->assignment,
                    s->counts);
  }
  // The speeds each kind can reach (people.h).
  s->counts->speeds_limited = LimitSpeedsToTheirKind(options_.people, &state_);
}

std::vector<StaticObservation> Estimator::ManageTracks(ScanInProgress* s) {
  const ScanAssociation association = s->association();
  // 7. Hits and misses (line 11), judged at the state after the updates; the take-overs of
  // lost movers' identities tagged at an earlier scan.
  const std::vector<ObjectPrediction> after_updates = s->predicted.At(state_);
  RecordHitsAndMisses(association, s->features.widths_m, s->interval.gap_s, options_,
                      after_updates, s->assignment, &state_);
  const std::vector<int> taken_over =
      TakeOverLostIdentities(s->utime, options_, s->assignment, &state_, s->counts);
  // Which measurements may start objects: an object that took its own measurement need not
  // block a second thing beside it (new_object_gate_skips_claimed_objects); the UNDECIDED
  // objects such a birth is beside forget the moving evidence the two things' measurements gave
  // (and, new_object_beside_claimed_restarts_state, start again from their own measurement)
  // before they are judged.
  const std::vector<double> birth_nis = NearestNisForBirths(
      s->features.measurements, s->gating, s->assignment, state_, options_);
  if (options_.new_object_gate_skips_claimed_objects) {  // off, birth_nis is nearest_nis
    RestartObjectsBesideBirths(ClaimedObjectsBesideBirths(s->gating, birth_nis, s->assignment,
                                                          options_.new_object_gate_dn_chi2),
                               association, s->assignment, options_, &state_);
  }
  // 8. Static or dynamic (line 12); then the standing people a walker took over (people.h).
  ClassifyObjects(association, s->gating.gated, options_, after_updates, s->assignment,
                  &state_, s->counts);
  const std::vector<uint8_t> measured = s->assignment.ObjectsMeasured();
  std::vector<int> removed = PersonTracksTakenOver(measured, options_.people, state_);
  s->counts->person_tracks_taken_over = static_cast<int>(removed.size());
  // One person moving between two tracks: the one that took this scan's measurement stays.
  const std::vector<int> in_turn = PersonTracksMeasuredInTurn(measured, options_.people, state_);
  s->counts->person_tracks_measured_in_turn = static_cast<int>(in_turn.size());
  for (int j : in_turn) {
    if (std::find(removed.begin(), removed.end(), j) == removed.end()) removed.push_back(j);
  }
  removed.insert(removed.end(), taken_over.begin(), taken_over.end());
  // The measurements of confirmed static landmarks, taken while the assignment's object indices
  // are still those of the state (pruning and new objects renumber them).
  std::vector<StaticObservation> static_observations =
      StaticObservations(s->features.measurements, s->assignment, state_);
  // 9. Re-acquisition tags, then pruning (line 11).
  const std::vector<int64_t> continues_id = TagPossibleContinuations(
      association, birth_nis, taken_over, options_, &s->predicted, state_, s->assignment);
  PruneObjects(s->utime, removed, options_, after_updates, s->assignment, &state_,
               s->counts, &archive_);
  // 10. New tracks outside gate dn of every object (line 13); their first sightings go to the
  // smoother too when asked (smoother_first_sightings).
  const std::vector<StaticObservation> first_sightings =
      AddNewObjects(association, birth_nis, continues_id, options_, s->assignment, &next_id_,
                    &state_, s->counts);
  if (options_.smoother_first_sightings) {
    static_observations.insert(static_observations.end(), first_sightings.begin(),
                               first_sightings.end());
  }
  return static_observations;
}

void Estimator::RestoreNearbyLandmarks(ScanInProgress* s) {
  s->counts->landmarks_restored = archive_.Restore(options_.window, &state_);
}

void Estimator::ArchiveDistantLandmarks(ScanInProgress* s) {
  s->counts->landmarks_archived = archive_.Archive(options_.window, &state_);
}

void Estimator::FinishScan(ScanInProgress* s) {
  ReportScanProblems(s->utime, *s->counts);
  s->counts->observation_predictions = s->predicted.computations();
  EnsureFiniteState(s->utime, s->counts);
  if (s->alignment_scan) {
    scan_motion_.Keep(std::move(*s->alignment_scan), state_.robot_pose(), s->utime,
                      s->alignment ? &*s->alignment : nullptr);
  }
}

std::optional<ScanAlignment> Estimator::AlignWithPreviousScan(const ScanInput& scan,
                                                              ScanInProgress* s) const {
  if (!options_.scan_alignment.enabled || odometry_.anchored()) return std::nullopt;
  s->alignment_scan = AlignmentScanOf(s->features.measurements, scan.lines, options_.sensor);
  return scan_motion_.MotionTo(*s->alignment_scan, s->interval.dt_s, options_.scan_alignment);
}

bool Estimator::AcceptScanTime(int64_t utime) {
  return AcceptTime("scan", utime, &scan_clock_);
}

void Estimator::EnsureFiniteState(int64_t utime, StepCounts* counts) {
  if (!PublishedStateIsFinite(state_)) {
    const double drift_sigma = options_.heading_drift_sigma_rad_per_m;
    const RecoveryOutcome recovery = RecoverFiniteState(
        last_finite_pose_, last_finite_pose_covariance_, drift_sigma * drift_sigma, &state_);
    ++counters_.state_recoveries;
    counts->state_recovered = 1;
    std::ostringstream text;
    text << "scan at utime " << utime << ": the state was not finite; ";
    if (recovery.robot_reset) {
      text << "started over from the last finite pose (map cleared)";
    } else {
      text << recovery.objects_removed << " object(s) with non-finite states removed";
    }
    Event(text.str());
  }
  last_finite_pose_ = state_.robot_pose();
  last_finite_pose_covariance_ = state_.robot_covariance();
}

ScanInterval Estimator::IntervalTo(int64_t utime) const {
  // Time since the previous scan (what went unseen) and the part of it the prediction covers
  // (max_prediction_s), over which a manoeuvre's velocity jump acts.
  ScanInterval interval;
  interval.first_scan = !last_scan_utime_;
  interval.gap_s = interval.first_scan ? 0.0 : SecondsBetween(utime, *last_scan_utime_);
  interval.dt_s = std::min(interval.gap_s, options_.max_prediction_s);
  return interval;
}

ValidatedFeatures Estimator::TakeFeatures(const std::vector<FeatureReading>& features,
                                          StepCounts* counts) {
  ValidatedFeatures validated = ValidateFeatures(features, options_);
  counts->features_at_edge_of_view = validated.at_edge_of_view;
  if (validated.over_cap > 0) {
    counts->features_over_cap = validated.over_cap;
    counters_.features_over_cap += validated.over_cap;
    Event(std::to_string(validated.over_cap) + " feature(s) beyond max_features_per_scan (" +
          std::to_string(options_.max_features_per_scan) + ") dropped, the nearest kept");
  }
  if (validated.rejected > 0) {
    counts->features_rejected = validated.rejected;
    counters_.features_rejected += validated.rejected;
    Event(std::to_string(validated.rejected) + " feature(s) rejected, first: " +
          validated.first_rejection);
  }
  return validated;
}

void Estimator::Predict(int64_t utime, const ScanInterval& interval,
                        const ScanAlignment* aligned) {
  const PredictionNotes notes =
      PredictToScan(utime, interval, options_, &odometry_, &state_, aligned);
  last_motion_ = notes.motion;
  if (notes.without_odometry) {
    ++counters_.scans_without_odometry;
    Event("scan at utime " + std::to_string(utime) + ": no odometry since the previous scan, " +
          (aligned != nullptr ? "moved by the alignment with the previous scan"
                              : "predicted with the last velocity"));
  }
  if (notes.time_gap) {
    ++counters_.time_gaps;
    std::ostringstream text;
    text << "scan at utime " << utime << ": " << interval.gap_s
         << " s since the previous scan (limit " << options_.max_time_gap_s
         << " s), uncertainty inflated";
    if (interval.gap_s > interval.dt_s) text << " as for " << interval.dt_s << " s";
    Event(text.str());
  }
}

void Estimator::UpdateLines(const ScanInput& scan, StepCounts* counts) {
  counts->lines = static_cast<int>(scan.lines.size());
  if (scan.lines.empty()) return;
  const LineGates gates{options_.gate_d1_chi2, options_.new_object_gate_dn_chi2,
                        options_.update_group_size};
  const LineStepCounts lines = UpdateLineLandmarks(scan.lines, scan.utime, options_.lines, gates,
                                                   options_.sensor, &next_id_, &state_,
                                                   &line_candidates_);
  counts->lines_rejected = lines.rejected;
  counts->line_updates = lines.level1_updates + lines.level2_updates;
  counts->lines_associated = lines.associated;
  counts->line_updates_skipped = lines.updates_skipped;
  counts->new_lines = lines.new_landmarks;
  counts->lines_refused = lines.refused;
  counts->updates_failed += lines.failed;
  counters_.lines_rejected += lines.rejected;
  counters_.lines_refused += lines.refused;
  if (lines.rejected > 0) {
    Event(std::to_string(lines.rejected) + " line feature(s) rejected, first: " +
          lines.first_rejection);
  }
  if (lines.refused > 0) {
    Event("scan at utime " + std::to_string(scan.utime) + ": " + std::to_string(lines.refused) +
          " new line landmark(s) refused, cap of " +
          std::to_string(options_.lines.max_landmarks) + " reached");
  }
}

void Estimator::DropPointsOnLines(ValidatedFeatures* features, StepCounts* counts) const {
  std::vector<Eigen::Vector2d> range_bearings;
  range_bearings.reserve(features->measurements.size());
  for (const PointMeasurement& m : features->measurements) {
    range_bearings.push_back(m.range_bearing);
  }
  const std::vector<uint8_t> on_line =
      PointsOnLineLandmarks(range_bearings, options_.lines, options_.sensor, state_);
  size_t kept = 0;
  for (size_t i = 0; i < on_line.size(); ++i) {
    if (on_line[i]) continue;
    features->measurements[kept] = features->measurements[i];
    features->widths_m[kept] = features->widths_m[i];
    ++kept;
  }
  counts->points_on_lines = static_cast<int>(on_line.size() - kept);
  features->measurements.resize(kept);
  features->widths_m.resize(kept);
}

void Estimator::ReportScanProblems(int64_t utime, const StepCounts& counts) {
  if (counts.objects_refused > 0) {
    counters_.object_cap_hits += counts.objects_refused;
    Event("scan at utime " + std::to_string(utime) + ": " +
          std::to_string(counts.objects_refused) + " new object(s) refused, cap of " +
          std::to_string(options_.max_objects) + " objects reached");
  }
  counters_.static_updates_skipped += counts.static_updates_skipped;
  if (counts.updates_failed > 0) {
    counters_.updates_failed += counts.updates_failed;
    Event("scan at utime " + std::to_string(utime) + ": " +
          std::to_string(counts.updates_failed) + " observation(s) numerically unusable");
  }
}

void Estimator::ReportEstimate(int64_t utime, ScanResult* result) const {
  result->processed = true;
  result->pose = state_.robot_pose();
  result->pose_covariance = state_.robot_covariance();
  result->motion = last_motion_;
  result->objects.reserve(static_cast<size_t>(state_.num_objects()));
  for (int j = 0; j < state_.num_objects(); ++j) {
    const ObjectRecord& record = state_.object(j).record;
    ObjectEstimate e;
    e.id = record.id;
    e.object_class = record.object_class;
    const bool has_velocity = state_.object(j).has_velocity();
    e.confirmed = ReportedConfirmed(record, has_velocity, utime, options_.tracks);
    e.reported = (ReportedTrack(record, has_velocity, utime, options_.tracks) &&
                  ShowsAPerson(record,
                               (state_.position(j) - state_.robot_pose().head<2>()).norm(),
                               options_.people)) ||
                 ReportedAtBirth(record, utime, options_.people);
    e.kind = record.kind;
    e.measured = record.last_seen_utime == utime;
    e.coasting_s = SecondsBetween(utime, record.last_seen_utime);
    e.position = state_.position(j);
    e.velocity = state_.velocity(j);
    e.covariance = state_.ObjectCovariance(j);
    e.first_seen_utime = record.first_seen_utime;
    e.last_seen_utime = record.last_seen_utime;
    e.hits = record.hits;
    result->objects.push_back(e);
  }
  result->archived_landmarks.reserve(static_cast<size_t>(archive_.size()));
  for (const auto& [id, landmark] : archive_.landmarks()) {
    ObjectEstimate e;
    e.id = id;
    e.object_class = landmark.record.object_class;
    e.kind = landmark.record.kind;
    e.confirmed = true;
    e.reported = true;
    e.coasting_s = SecondsBetween(utime, landmark.record.last_seen_utime);
    e.position = landmark.position_m;
    e.covariance.topLeftCorner<2, 2>() = landmark.covariance_m2;
    e.first_seen_utime = landmark.record.first_seen_utime;
    e.last_seen_utime = landmark.record.last_seen_utime;
    e.hits = landmark.record.hits;
    result->archived_landmarks.push_back(e);
  }
  result->lines.reserve(static_cast<size_t>(state_.num_lines()));
  for (int k = 0; k < state_.num_lines(); ++k) {
    const LineRecord& record = state_.line(k).record;
    LineEstimate e;
    e.id = record.id;
    e.line = state_.line_params(k);
    e.covariance = state_.LineCovariance(k);
    e.from_m = PointOnLine(e.line, record.extent_from_m);
    e.to_m = PointOnLine(e.line, record.extent_to_m);
    e.hits = record.hits;
    e.first_seen_utime = record.first_seen_utime;
    e.last_seen_utime = record.last_seen_utime;
    result->lines.push_back(e);
  }
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
