#include "estimator/track_management.h"

#include <algorithm>
#include <bitset>
#include <cmath>

#include "common/utime.h"
#include "estimator/angle.h"

namespace slammtt {

ObjectRecord NewObjectRecord(int64_t id, int64_t utime, ObjectClass object_class) {
  ObjectRecord record;
  record.id = id;
  record.object_class = object_class;
  record.first_seen_utime = utime;
  record.last_seen_utime = utime;
  record.last_update_utime = utime;
  record.class_change_utime = utime;
  record.hits = 1;
  record.hits_with_velocity = 1;
  record.recent_hits = 1;
  record.recent_scans = 1;
  return record;
}

namespace {
// The kind of the scans so far decides (a new object's: of its first measurement).
int HitsNeededToConfirm(const ObjectRecord& record, const TrackManagementOptions& options) {
  return record.kind == ObjectKind::kPerson ? options.confirm_person_hits : options.confirm_hits;
}
}  // namespace

void RecordHit(int64_t utime, const TrackManagementOptions& options, ObjectRecord* record) {
  ++record->hits;
  ++record->hits_with_velocity;
  record->recent_hits = (record->recent_hits << 1) | 1u;
  record->recent_scans = (record->recent_scans << 1) | 1u;
  record->recent_visible_misses <<= 1;
  record->last_seen_utime = utime;
  record->unseen_in_view_s = 0.0;
  record->unseen_observable_s = 0.0;
  record->reentered_unseen = false;
  if (record->confirmed) return;
  const int window = options.confirm_window_scans;
  const int hits_in_window = window <= 0 ? record->hits : HitsInLastScans(*record, window);
  const int needed = HitsNeededToConfirm(*record, options);
  if (hits_in_window >= needed) record->confirmed = true;
}

namespace {
uint32_t LastScansMask(int window_scans) {
  if (window_scans <= 0) return 0u;
  return window_scans >= 32 ? ~0u : (1u << window_scans) - 1u;
}
}  // namespace

int HitsInLastScans(const ObjectRecord& record, int window_scans) {
  return static_cast<int>(
      std::bitset<32>(record.recent_hits & LastScansMask(window_scans)).count());
}

int VisibleMissesInLastScans(const ObjectRecord& record, int window_scans) {
  return static_cast<int>(
      std::bitset<32>(record.recent_visible_misses & LastScansMask(window_scans)).count());
}

int MissesInLastScans(const ObjectRecord& record, int window_scans) {
  return static_cast<int>(
      std::bitset<32>(record.recent_scans & ~record.recent_hits & LastScansMask(window_scans))
          .count());
}

void RecordMiss(double dt_s, bool in_geometry, bool expected_visible, ObjectRecord* record) {
  // One scan is one chance to see the object, whatever the time since the previous one (after
  // a time gap nobody was looking in between): at most kMaxMissPerScan_s per scan.
  const double miss_s = std::min(dt_s, kMaxMissPerScan_s);
  record->recent_hits <<= 1;
  record->recent_scans = (record->recent_scans << 1) | 1u;
  record->recent_visible_misses =
      (record->recent_visible_misses << 1) | (expected_visible ? 1u : 0u);
  if (expected_visible) record->unseen_in_view_s += miss_s;
  if (in_geometry) record->unseen_observable_s += miss_s;
}

bool CanStillConfirm(const ObjectRecord& record, const TrackManagementOptions& options) {
  const int window = options.confirm_window_scans;
  const int needed = HitsNeededToConfirm(record, options);
  if (window <= 0 || needed <= 1) return true;  // (one hit confirms: nothing to lose)
  // k coming scans measured, with the window's other window - k scans from the past; k < needed,
  // or the coming hits alone would do it (a new object's confirmation).
  for (int k = 1; k < std::min(needed, window); ++k) {
    if (HitsInLastScans(record, window - k) + k >= needed) return true;
  }
  return false;
}

bool ShouldPrune(const ObjectRecord& record, bool has_velocity, int64_t utime, bool out_of_view,
                 double position_sigma_m, const TrackManagementOptions& options) {
  const double unseen_s = SecondsBetween(utime, record.last_seen_utime);
  if (!record.confirmed) {
    const bool prune_unconfirmable =
        options.tentative_prune_unconfirmable ||
        (options.other_tentative_prune_unconfirmable && record.kind != ObjectKind::kPerson);
    if (prune_unconfirmable && !CanStillConfirm(record, options)) return true;
    return unseen_s > options.tentative_prune_unseen_s;
  }
  if (has_velocity) {
    if (options.prune_unseen_visible_s > 0.0 &&
        record.unseen_in_view_s > options.prune_unseen_visible_s) {
      return true;
    }
    if (record.object_class == ObjectClass::kMoving) {
      if (unseen_s > options.prune_out_of_view_s) return true;
      if (out_of_view) return position_sigma_m > options.max_coast_sigma_m;
      return record.unseen_observable_s > options.prune_unseen_s;
    }
    return unseen_s > options.prune_unseen_s;
  }
  return options.static_prune_unseen_in_view_s > 0.0 &&
         record.unseen_in_view_s > options.static_prune_unseen_in_view_s;
}

bool ReportedConfirmed(const ObjectRecord& record, bool has_velocity, int64_t utime,
                       const TrackManagementOptions& options) {
  if (!record.confirmed) return false;
  if (!has_velocity) return true;
  if (options.coast_confirmed_s > 0.0 && record.unseen_in_view_s > options.coast_confirmed_s) {
    return false;
  }
  const double unseen_s = SecondsBetween(utime, record.last_seen_utime);
  return options.coast_unseen_s <= 0.0 || unseen_s <= options.coast_unseen_s;
}

bool ReportedTrack(const ObjectRecord& record, bool has_velocity, int64_t utime,
                   const TrackManagementOptions& options) {
  if (!ReportedConfirmed(record, has_velocity, utime, options)) return false;
  if (!has_velocity && record.kind != ObjectKind::kPerson) return true;
  if (has_velocity) {
    const bool person = record.kind == ObjectKind::kPerson;
    const int needed = !person ? options.report_other_hits
                       : record.object_class == ObjectClass::kMoving ? options.report_person_hits
                                                                      : 0;
    // Misses, not hits: an object younger than the window is judged by the scans it lived.
    const int window = options.report_window_scans;
    const int misses = person ? MissesInLastScans(record, window)
                              : VisibleMissesInLastScans(record, window);
    if (needed > 0 && misses > window - needed) return false;
  }
  return SecondsBetween(utime, record.last_seen_utime) <= options.report_measured_within_s;
}

bool SurelyInGeometry(const Eigen::Vector2d& predicted, double sigma_m, double max_range_m,
                      const FieldOfView& view) {
  const double range = predicted(0);
  const double margin = 2.0 * sigma_m;
  if (!(range + margin <= max_range_m)) return false;
  if (view.full()) return true;
  const double angle_margin = range > margin ? std::asin(margin / range) : M_PI;
  return view.ContainsWithMargin(predicted(1), angle_margin);
}

bool ExpectedVisible(const Eigen::Vector2d& predicted, double sigma_m,
                     const std::vector<Eigen::Vector3d>& features_range_bearing_width,
                     double max_range_m, const FieldOfView& view, double shadow_radius_m) {
  const double range = predicted(0);
  if (!SurelyInGeometry(predicted, sigma_m, max_range_m, view)) return false;
  constexpr double kObjectRadius_m = 0.3;
  constexpr double kRangeMargin_m = 1.0;
  for (const Eigen::Vector3d& f : features_range_bearing_width) {
    if (f(0) > range + kRangeMargin_m) continue;
    const double half_width = std::max(0.5 * f(2), shadow_radius_m) + kObjectRadius_m;
    const double angle = std::atan2(half_width, std::max(f(0), 1e-3));
    if (std::abs(WrapAngle(predicted(1) - f(1))) < angle) return false;
  }
  return true;
}

void VisitTrackManagementOptions(OptionVisitor* v, TrackManagementOptions* t) {
  using R = OptionRange;
  v->Int("confirm_hits", &t->confirm_hits, R::Between(1, 1000),
         "hits that confirm a tentative object (T_th; M of M-of-N)");
  v->Int("confirm_window_scans", &t->confirm_window_scans, R::Between(0, 32),
         "N of M-of-N: confirm_hits of the last N scans (0: at any time)");
  v->Int("confirm_person_hits", &t->confirm_person_hits, R::Between(1, 1000),
         "M of M-of-N for an object of kind person");
  v->Double("prune_unseen_s", &t->prune_unseen_s, R::AtLeast(0),
            "an object with velocity unseen this long goes (paper 5.1: 3.5 s)");
  v->Double("tentative_prune_unseen_s", &t->tentative_prune_unseen_s, R::AtLeast(0),
            "a tentative object unseen this long goes");
  v->Bool("tentative_prune_unconfirmable", &t->tentative_prune_unconfirmable,
          "a tentative object that can no longer be confirmed goes at once");
  v->Bool("other_tentative_prune_unconfirmable", &t->other_tentative_prune_unconfirmable,
          "the same for a tentative object that is not of kind person");
  v->Double("static_prune_unseen_in_view_s", &t->static_prune_unseen_in_view_s, R::AtLeast(0),
            "a landmark missed this long where it should be seen goes (0: never)");
  v->Double("prune_unseen_visible_s", &t->prune_unseen_visible_s, R::AtLeast(0),
            "an object with velocity missed this long where it should be seen goes");
  v->Double("shadow_radius_m", &t->shadow_radius_m, R::AtLeast(0),
            "half-width of what a point feature hides, at its range");
  v->Double("coast_confirmed_s", &t->coast_confirmed_s, R::AtLeast(0),
            "reported unconfirmed after this long missed where it should be seen (0: off)");
  v->Double("coast_unseen_s", &t->coast_unseen_s, R::AtLeast(0),
            "reported unconfirmed after this long unseen (0: off)");
  v->Double("report_measured_within_s", &t->report_measured_within_s, R::AtLeast(0),
            "a reported track was measured within this time (track_t.reported)");
  v->Int("report_person_hits", &t->report_person_hits, R::Between(0, 32),
         "a MOVING person is reported while measured in this many of the window (0: off)");
  v->Int("report_other_hits", &t->report_other_hits, R::Between(0, 32),
         "an object with velocity that is no person: the same (0: off)");
  v->Int("report_window_scans", &t->report_window_scans, R::Between(1, 32),
         "the last scans that report_person_hits and report_other_hits count");
  v->Double("prune_out_of_view_s", &t->prune_out_of_view_s, R::AtLeast(0),
            "a MOVING object out of view goes after this long");
  v->Double("max_coast_sigma_m", &t->max_coast_sigma_m, R::Above(0),
            "a MOVING object out of view goes when its position sigma exceeds this");
  v->Double("reacquire_speed_mps", &t->reacquire_speed_mps, R::AtLeast(0),
            "walking speed bound of re-acquisition of lost movers (0: off)");
}

}  // namespace slammtt
