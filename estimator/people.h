// People and other movers: what kind an object is, the process noise of each kind, and the
// speeds each kind can plausibly reach.
//
// Kind: a person feature (perception's legs paired into a person, or one leg alone with a
// covariance grown by the leg's offset from the person's centre; docs/perception.md) is one
// measurement of a person; every other point feature is a measurement of something else. An
// object is of kind PERSON while more than half of its measured scans were person features
// (RecordMeasurementKind), so one scan in which a person's legs were not paired (two leg
// clusters, one taken as the person's single leg, the other as a point) does not change what it
// is. Kind and class are independent: a standing person is a STATIC object of kind PERSON,
// tracked like every landmark but never part of the static map (MAP, estimator_stage.h).
//
// Speed gate: after the updates of a scan, the velocity estimate of every object with velocity
// states is projected onto the speeds its kind can reach, |v| <= max_speed (the mean only:
// estimate projection of a constrained Kalman filter, Simon and Chia, "Kalman filtering with
// state equality constraints", IEEE Trans. Aerospace and Electronic Systems 38(1), 2002; the
// inequality is active only when violated, and the covariance is left as it is). Limits, from
// published speeds:
//  - people: 3.0 m/s. Adults' fastest walking speeds are 1.75-2.53 m/s (Bohannon, "Comfortable
//    and maximum walking speed of adults aged 20-79 years", Age and Ageing 26(1), 1997: means of
//    each age and sex group), comfortable walking 1.27-1.46 m/s; people hurrying over ground
//    mix walking and running between 1.9 and 3.0 m/s and mostly run at 3.0 m/s (Baker, Long
//    and Srinivasan, "Overground gait transitions are not sharp but involve gradually changing
//    walk-run mixtures even over long distances", arXiv 2501.00720, 2025). 3 m/s is above
//    every walking person and a jog indoors; a faster estimate is a mis-association or a
//    velocity that absorbed the robot's error, not a person.
//  - any other mover: 12.5 m/s, above the fastest human sprint measured (Usain Bolt's 100 m
//    world record, Berlin 2009: 20 m in 1.61 s between 60 and 80 m, 12.4 m/s, in the IAAF's
//    biomechanical analysis of those championships). Nothing indoors that a laser sees as a
//    compact object moves faster.
// 0 turns a limit off. Counted per scan (StepCounts::speeds_limited).
//
// Two people cannot stand closer together than their bodies allow: hips are about 0.2 m wide
// and two people side by side are 0.45 m or more apart centre to centre, so two person tracks
// closer than min_separation_m are one person seen twice. Two rules follow:
//  - a person who stood still (a STATIC track of kind PERSON, never in the map) and walks off
//    leaves the gates of their standing track, and their features start a new track that
//    becomes MOVING; the standing track, no longer measured, is reported as a person standing
//    there for every scan it coasts (scripts/people-errors.py: person/STATIC/coasting false
//    positives). When such a STATIC person track got no measurement in a scan and a confirmed
//    MOVING person track that did lies within taken_over_within_m of it and was born no
//    earlier than taken_over_born_within_s before the standing track's last measurement (its
//    life began where the standing track's measurements ended), the moving track has taken
//    over its person and the standing track is removed (PersonTracksTakenOver, counted in
//    StepCounts::person_tracks_taken_over). Without the birth condition, any old mover passing
//    by (a walker who occludes a standing person; in a mine, rock faces taken for a person
//    standing and another for a person moving) removes a standing track whose measurements
//    were correcting the robot's pose: the real Mines exp1 map got worse (RMS to its own lines
//    0.0586 -> 0.0631 m in one run). With the birth condition it costs exp1 less than a 1 %
//    change of a noise floor moves it (median of five runs: wall spread 0.0963 -> 0.0988 m,
//    RMS 0.0614 -> 0.0631 m; docs/targets.md, "Real recordings: one run against five") and
//    raises office people MOTA (seeds 1-20 worst 0.768 -> 0.804): on, at 0.5 m;
//  - a person feature that would start a new object within min_separation_m of an object of
//    kind PERSON (one of the state's, or one born earlier in the same scan) is that person:
//    its legs split into two person features, or a feature just outside the track's gate dn.
//    It starts no duplicate track and is left unused like every free measurement inside gate dn
//    (new_objects.h; counted in StepCounts::person_births_joined).
// 0 turns either rule off.
#pragma once

#include <cstdint>
#include <vector>

#include "common/options_schema.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct PeopleOptions {
  // sigma_Q of eq. 8 for MOVING people (MOVING objects of other kinds:
  // EstimatorOptions::mover_acceleration_sigma_mps2).
  double acceleration_sigma_mps2 = 0.02;
  double max_speed_mps = 3.0;         // people (see above); 0: no limit
  double other_max_speed_mps = 12.5;  // every other mover; 0: no limit
  double min_separation_m = 0.4;      // no person track is born closer to another (see above)
  double taken_over_within_m = 0.5;   // a standing track this near a measured walker goes
  double taken_over_born_within_s = 1.0;  // ... born at most this long before its last hit
  // Two person tracks this near, measured in turn, are one person (see
  // PersonTracksMeasuredInTurn); 0: off.
  double measured_in_turn_within_m = 1.0;
  int measured_in_turn_window_scans = 10;  // ... over this many scans
  // A new person track is reported in the scan it is born in when the person feature that
  // started it is two legs paired with at least this confidence (see ReportedAtBirth); 0: off.
  double report_pair_births_confidence = 0.85;
  double report_pair_births_clear_m = 1.0;  // ... and no person or mover this near (see there)
  // Evidence a track of kind PERSON must show before it is reported (see ShowsAPerson):
  // while farther than report_far_m from the robot, report_far_min_hits scans with a
  // measurement (ObjectRecord::hits; on) ...
  double report_far_m = 6.0;
  int report_far_min_hits = 6;
  // ... and, off (measured, they cost the simulated people more than they save on
  // negative_2), scans of two legs paired (ObjectRecord::pair_hits), 0: off;
  int report_min_pair_hits = 0;
  // the share of its measured scans that were person features (person_hits / hits; its kind
  // asks for more than half) while it is not MOVING, 0: off.
  double report_min_person_share = 0.0;
};

// Whether a tentative object is reported in the scan it was born in (utime): a person seen as
// two legs paired (birth_pair_confidence >= report_pair_births_confidence) is a person before
// it is a track. Confirmation needs confirm_person_hits scans (track_management.h), so every
// person who comes into view or whose track was lost was missed in the first scan of the new
// track (scripts/people-errors.py: "tentative"). Only the birth scan: a track seen once and
// never again is not reported while it coasts (a leg split off its person, a pair of chair
// legs), and from the next scan on confirmation decides as for every track. Nor a birth within
// report_pair_births_clear_m of an object of kind PERSON or a MOVING one (BesideAPersonOrMover):
// that is most likely a person whose track fell behind or was not reported in this scan, and
// reported, the new track takes the person's correspondence from the old one (CLEAR-MOT carries
// correspondences over), which then counts as a false track and a switch when it comes back.
// Measured (scripts/measure-estimator.py, seeds 1-20, people MOTA worst (seed) / median): any
// pair (confidence 0.01) took office from 0.766 (11) / 0.836 to 0.768 (11) / 0.839 and corridor
// from 0.804 (14) / 0.855 to 0.811 (14) / 0.865, but pairs of furniture legs on the real
// negative_2 recording (no person in it) became people: 25.9 -> 36.3 reported identities per
// minute (0.7: 28.0). At 0.85 negative_2 and leg_tracker_demo are unchanged (25.9 and 18.1 per
// minute) and office is 0.768 (11) / 0.837, corridor 0.809 (14) / 0.859. Without the
// clearance, office's worst seed fell to 0.751 (the correspondences taken).
bool ReportedAtBirth(const ObjectRecord& record, int64_t utime, const PeopleOptions& options);

// Whether a track of kind PERSON, range_m from the robot, has shown enough evidence of a
// person to be reported as one (the reporting rules of track_management.h, ReportedTrack,
// apply as well; any other kind: true; a pair birth is reported at birth all the same,
// ReportedAtBirth).
// - Far away, a person's shape says little: a leg of 0.12 m shows 3.3 beams of a 0.35-degree
//   scanner at 6 m (3.8 of a 0.25-degree one), and 3 is the fewest a point feature has
//   (docs/perception.md), so a table or chair leg there makes person features as readily as a
//   person does, and the track's evidence is its persistence: report_far_min_hits scans.
//   On the real negative_2 recording (no person in it) every false person was reported by
//   confirmation at its 2nd-23rd hit, half of them first beyond 5 m (median 4.9 m; the
//   simulated offices' reported people: median 2.3 m, 12 of 231 beyond 5 m). 6 m and 6 hits
//   were chosen by scoring main's negative_2 and demo logs again offline (4-6 m with 4-6 hits
//   give 17.6-22.8 per minute: no knife edge), so negative_2 is not a held-out figure. 6 m / 6 hits:
//   negative_2 25.9 -> 18.7 person identities per minute (median of five runs); the simulated
//   people's MOTA on office and corridor seeds 1-30 the same or higher (three seeds up by
//   0.002-0.014), leg_tracker_demo unchanged (its scanner reaches 5.6 m). docs/targets.md,
//   "negative_2: which rule reports each false person".
// - Off: one leg alone is a narrow cylinder as a chair or table leg is
//   (report_min_pair_hits); a track that does not walk and whose measurements were as often
//   point features as person features is not clearly a person (report_min_person_share; a
//   MOVING track's motion is evidence of its own, and the demo's walkers are first seen as
//   points). Medians of five runs against 25.9 identities per minute, and office people MOTA
//   seeds 1-20 worst (seed) / median against 0.804 (13) / 0.841: one pair 18.7, but 0.773 (13)
//   / 0.816 (the simulated people's tracks are often born and kept on one leg); a share of 0.7
//   21.8, but 0.795 (13) / 0.834 (standing people unreported), and the demo's agreement with
//   the leg pairs 0.385 -> 0.378.
bool ShowsAPerson(const ObjectRecord& record, double range_m, const PeopleOptions& options);

// The schema of these options (common/options_schema.h; keys in EstimatorOptions' group
// `people`).
void VisitPeopleOptions(OptionVisitor* visitor, PeopleOptions* options);

// The kind a record's measured scans give it: PERSON when person_hits > hits / 2.
ObjectKind KindOfRecord(const ObjectRecord& record);

// Accounts the kind of one scan's measurement of the object (its hits are already counted)
// and updates record->kind.
void RecordMeasurementKind(bool person_measurement, ObjectRecord* record);

// The largest plausible speed of an object of `kind` (0: no limit).
double MaxSpeedOfKind(ObjectKind kind, const PeopleOptions& options);

// Scales every velocity estimate faster than its kind's limit down to the limit (see above).
// Returns how many were limited.
int LimitSpeedsToTheirKind(const PeopleOptions& options, SlamState* state);

// Whether `point_m` (map frame) lies closer than min_separation_m to an object of kind PERSON
// (false when min_separation_m is 0).
bool TooCloseToAPerson(const Eigen::Vector2d& point_m, const PeopleOptions& options,
                       const SlamState& state);

// Whether `point_m` (map frame) lies within report_pair_births_clear_m of an object of kind
// PERSON or of class MOVING.
bool BesideAPersonOrMover(const Eigen::Vector2d& point_m, const PeopleOptions& options,
                          const SlamState& state);

// Two person tracks within measured_in_turn_within_m of each other, both alive over the last
// measured_in_turn_window_scans scans, never measured in the same scan of them and measured in
// turn (the measurements went from one to the other and back at least once), where one got a
// measurement this scan and the other did not: one person who moves between two tracks that
// each take the measurements near them (a person pacing on the spot, each track STATIC; two
// people side by side give two person features in most scans and both tracks are measured
// together). Returns the unmeasured ones, increasing.
std::vector<int> PersonTracksMeasuredInTurn(const std::vector<uint8_t>& measured,
                                            const PeopleOptions& options, const SlamState& state);

// The STATIC person tracks that a MOVING person track took over (see above), increasing.
// `measured`: per object of the state, whether it got a measurement this scan.
std::vector<int> PersonTracksTakenOver(const std::vector<uint8_t>& measured,
                                       const PeopleOptions& options, const SlamState& state);

}  // namespace slammtt
