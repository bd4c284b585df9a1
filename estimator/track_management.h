// Life cycle of the estimator's objects (paper Algorithm 2, lines 11 and 13): creation of
// tentative objects, confirmation after enough hits (the track threshold T_th), and pruning of
// objects unseen for too long (paper section 5.1: 3.5 s).
//
// Pruning rules:
//   - a tentative object is dropped after tentative_prune_unseen_s without a measurement
//     (a false alarm must not live 3.5 s), and at once when it can no longer be confirmed by
//     the hits it has (tentative_prune_unconfirmable; other_tentative_prune_unconfirmable for
//     objects not of kind PERSON);
//   - a confirmed object with velocity states (moving or undecided) is dropped after
//     prune_unseen_s without a measurement, as in the paper; for a confirmed MOVING object only
//     the time its prediction spent inside the field of view and range counts: out of view it
//     cannot be seen, so it is kept until prune_out_of_view_s in all or until its position
//     standard deviation exceeds max_coast_sigma_m, to be re-associated when it comes back (a
//     person who walked out of a 180-degree view and returns keeps its identity). It is
//     dropped sooner, after
//     prune_unseen_visible_s during which it should have been seen: inside the field of view
//     and range and not in the shadow of anything the scan saw in front of it (negative
//     information: a person who turned away from the track's prediction is not occluded, and
//     the track that kept going straight is a ghost; an occluded person is coasted the full
//     3.5 s);
//   - a static landmark is kept while out of view (the paper makes pruning static objects
//     optional; a map that forgets what the robot cannot see cannot close a loop), and dropped
//     after static_prune_unseen_in_view_s during which it should have been seen (as above) and
//     got no measurement (it was removed, or it was a person who walked away). 0 disables it.
#pragma once

#include <cstdint>
#include <vector>

#include "common/options_schema.h"

#include "estimator/field_of_view.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Reporting: a confirmed object with velocity states that should have been seen (see
// ExpectedVisible) for longer than coast_confirmed_s without a measurement, or that has gone
// unseen for longer than coast_unseen_s whatever the reason, is reported as not confirmed
// (ObjectEstimate::confirmed) until a measurement supports it again. Its existence is no longer
// backed by evidence, as a track's existence probability decays with the scans in which it
// could have been detected and was not in IPDA (Musicki, Evans and Stankovic, IEEE TAC 1994);
// the track is still kept for re-association until it is pruned. Static landmarks are not
// affected (the map keeps what the robot cannot see). 0 disables either rule.
struct TrackManagementOptions {
  int confirm_hits = 3;                       // T_th: M of M-of-N
  // N of M-of-N: a tentative object is confirmed when confirm_hits of its last
  // confirm_window_scans scans (at most 32) had a measurement, so that a cluster seen now and
  // then (clutter, a reflection, a chair leg at the edge of detection) never accumulates hits
  // into a confirmed track. 0: confirm_hits measured scans at any time (the rule before).
  int confirm_window_scans = 5;
  // M of M-of-N for an object of kind PERSON (people.h: its measurements were person
  // features), in the same window. A person is recognised by its shape (two legs paired), not
  // only by its motion as anything else is, so two scans are enough evidence: half of the
  // people score's misses on office and corridor were the first scans of a person whose track
  // was still tentative (scripts/people-errors.py, seeds 1-10: 271 of 563 and 264 of 529). 2
  // raised people MOTA on seeds 1-30 (office worst 0.753 -> 0.757, corridor 0.794 -> 0.801;
  // docs/targets.md) and took the real negative_2 recording (no person in it) from 27.0 to
  // 30.1 reported person identities per minute (3 more in 0.96 min).
  int confirm_person_hits = 2;
  double prune_unseen_s = 3.5;                // paper section 5.1
  double tentative_prune_unseen_s = 1.0;
  // A tentative object that can no longer reach its confirmation (confirm_hits, or
  // confirm_person_hits for a person, of a window of confirm_window_scans scans) with the hits
  // it has, even if every coming scan measures it, is pruned at once instead of after
  // tentative_prune_unseen_s: it has missed too many scans of its window. Kept, it would only
  // hold a measurement's place (take the measurement of whatever is there now, so that no new
  // object starts from it) or start a duplicate beside that new object; a new object born of
  // the same measurements is confirmed as soon as it could have been. No effect with
  // confirm_window_scans 0.
  bool tentative_prune_unconfirmable = false;
  // The same rule for a tentative object that is not of kind PERSON only (people.h): a person
  // whose legs were missed for a few scans keeps its tentative track (with the rule for all,
  // corridor people MOTA's worst seed fell 0.804 -> 0.764), while a cluster seen once and again
  // a second later a metre away goes before its second sighting makes it a fast mover. Off by
  // default, as the classifier's other_moving_evidence_min_hits that it goes with
  // (motion_classifier.h: what both give, what they cost on the real recordings).
  bool other_tentative_prune_unconfirmable = false;
  double static_prune_unseen_in_view_s = 3.5;
  double prune_unseen_visible_s = 1.0;
  double shadow_radius_m = 0.4;  // angular half-width of what a point feature hides, at its range
  double coast_confirmed_s = 0.5;
  double coast_unseen_s = 0.75;
  // A track counts as reported (track_t.reported: what a user is shown, what slammtt-eval
  // scores) when it is confirmed (above) and was measured within this time; a static landmark
  // that is not a person is reported while confirmed (it is the map).
  double report_measured_within_s = 0.5;
  // A confirmed MOVING person counts as reported only while it had a measurement in
  // report_person_hits of its last report_window_scans scans (at most 32; an object younger
  // than the window: at most window - M misses in the scans it lived); any other object with
  // velocity states that is not a person, while it missed at most window - report_other_hits
  // of them where it should have been seen (ExpectedVisible: occlusion is no evidence). A
  // track's existence probability falls with each scan without a detection (IPDA: Musicki,
  // Evans and Stankovic, IEEE TAC 1994), faster where false detections are more likely: any
  // mover other than a person is found only by its motion, and a cluster that comes and goes
  // (a wall at the edge of range seen through dropouts, a door jamb, mixed pixels) moves as
  // much as it jumps. A walking person's track missed in 3 of 5 scans, occluded or not, has
  // mostly lost its person to another track (a duplicate born when it fell behind at a turn,
  // or a leg taken for a second person). A standing person (STATIC or UNDECIDED) is seen less
  // regularly (legs together, one leg hidden) and keeps the report_measured_within_s rule
  // alone. 0: off.
  int report_person_hits = 3;
  int report_other_hits = 4;
  int report_window_scans = 5;
  double prune_out_of_view_s = 30.0;
  double max_coast_sigma_m = 2.5;
  // Re-acquisition of lost movers (reacquisition.h): the largest speed at which a person is
  // assumed to have walked while unseen. 0 disables re-acquisition.
  double reacquire_speed_mps = 2.0;
};

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `tracks`).
void VisitTrackManagementOptions(OptionVisitor* visitor, TrackManagementOptions* options);

// Whether an object is reported as confirmed at utime (see coast_confirmed_s).
bool ReportedConfirmed(const ObjectRecord& record, bool has_velocity, int64_t utime,
                       const TrackManagementOptions& options);

// Whether an object is a reported track at utime (see report_measured_within_s,
// report_person_hits and report_other_hits).
bool ReportedTrack(const ObjectRecord& record, bool has_velocity, int64_t utime,
                   const TrackManagementOptions& options);

// A fresh record for an object first seen at utime.
ObjectRecord NewObjectRecord(int64_t id, int64_t utime, ObjectClass object_class);

// How many of the object's last `window_scans` scans (at most 32) had a measurement.
int HitsInLastScans(const ObjectRecord& record, int window_scans);

// How many of the object's last `window_scans` scans (at most 32) of its life had none.
int MissesInLastScans(const ObjectRecord& record, int window_scans);

// How many of them had none where it should have been seen (RecordMiss's expected_visible).
int VisibleMissesInLastScans(const ObjectRecord& record, int window_scans);

// Marks a scan in which the object got a measurement (confirmation: confirm_hits of the last
// confirm_window_scans scans).
void RecordHit(int64_t utime, const TrackManagementOptions& options, ObjectRecord* record);

// Accounts a scan of dt_s without a measurement (in_geometry: the prediction lies inside the
// field of view and range; expected_visible: see ExpectedVisible). A scan counts for at most
// kMaxMissPerScan_s (the period of a 5 Hz sensor).
inline constexpr double kMaxMissPerScan_s = 0.2;
void RecordMiss(double dt_s, bool in_geometry, bool expected_visible, ObjectRecord* record);

// Whether a tentative object can still be confirmed by a window (confirm_window_scans) that
// holds one of its past hits: some k of the coming scans, all measured, and the hits among its
// last confirm_window_scans - k scans make the hits needed (confirm_hits, or
// confirm_person_hits for a person). Any object could be confirmed by hits still to come alone;
// it would then be a new object. True when confirm_window_scans is 0.
bool CanStillConfirm(const ObjectRecord& record, const TrackManagementOptions& options);

// Whether the object should be removed at utime. `out_of_view`: its prediction lies outside the
// field of view or the sensor's range; `position_sigma_m`: the largest standard deviation of its
// position estimate.
bool ShouldPrune(const ObjectRecord& record, bool has_velocity, int64_t utime, bool out_of_view,
                 double position_sigma_m, const TrackManagementOptions& options);

// Whether a prediction (range, bearing) with position standard deviation sigma_m lies inside
// the field of view and range with a margin of 2 sigma (the object is surely there, not merely
// its estimate).
bool SurelyInGeometry(const Eigen::Vector2d& predicted, double sigma_m, double max_range_m,
                      const FieldOfView& view);

// Whether an object predicted at `predicted` (range, bearing) should have produced a feature:
// SurelyInGeometry up to max_range_m, and not behind any of the scan's features. A feature at
// (r, b) of width w hides the bearings within atan((max(w / 2, shadow_radius_m) + object
// radius) / r) of b beyond range r - 1 m (a person merged with a neighbour into one cluster
// hides it too).
bool ExpectedVisible(const Eigen::Vector2d& predicted, double sigma_m,
                     const std::vector<Eigen::Vector3d>& features_range_bearing_width,
                     double max_range_m, const FieldOfView& view, double shadow_radius_m);

}  // namespace slammtt
