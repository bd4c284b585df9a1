#include "estimator/people.h"

#include "common/utime.h"

namespace slammtt {

void VisitPeopleOptions(OptionVisitor* v, PeopleOptions* o) {
  using R = OptionRange;
  v->Double("acceleration_sigma_mps2", &o->acceleration_sigma_mps2, R::AtLeast(0),
            "process noise sigma_Q (eq. 8) of MOVING people");
  v->Double("max_speed_mps", &o->max_speed_mps, R::AtLeast(0),
            "speed gate of people: faster estimates are limited (0: off)");
  v->Double("other_max_speed_mps", &o->other_max_speed_mps, R::AtLeast(0),
            "speed gate of every other mover (0: off)");
  v->Double("min_separation_m", &o->min_separation_m, R::AtLeast(0),
            "no person track is born closer than this to another (0: off)");
  v->Double("taken_over_within_m", &o->taken_over_within_m, R::AtLeast(0),
            "an unmeasured STATIC person this near a measured MOVING one goes (0: off)");
  v->Double("measured_in_turn_within_m", &o->measured_in_turn_within_m, R::AtLeast(0),
            "two person tracks this near that are measured in turn are one person (0: off)");
  v->Int("measured_in_turn_window_scans", &o->measured_in_turn_window_scans, R::Between(3, 32),
         "... judged over this many scans");
  v->Double("taken_over_born_within_s", &o->taken_over_born_within_s, R::AtLeast(0),
            "... born at most this long before the STATIC one's last measurement");
  v->Double("report_pair_births_confidence", &o->report_pair_births_confidence, R::Between(0, 1),
            "a new person track of two legs this confident is reported at birth (0: off)");
  v->Double("report_pair_births_clear_m", &o->report_pair_births_clear_m, R::AtLeast(0),
            "... unless a person or mover lies this near");
  v->Double("report_far_m", &o->report_far_m, R::AtLeast(0),
            "a person track farther from the robot needs more hits to be reported (0: off)");
  v->Int("report_far_min_hits", &o->report_far_min_hits, R::Between(0, 1000),
         "... this many (ObjectRecord::hits)");
  v->Int("report_min_pair_hits", &o->report_min_pair_hits, R::Between(0, 1000),
         "a person track is reported once this many scans measured two legs paired (0: off)");
  v->Double("report_min_person_share", &o->report_min_person_share, R::Between(0, 1),
            "... and unless MOVING, person features made this share of its hits (0: off)");
}

bool ShowsAPerson(const ObjectRecord& record, double range_m, const PeopleOptions& options) {
  if (record.kind != ObjectKind::kPerson) return true;
  if (options.report_far_m > 0.0 && range_m > options.report_far_m &&
      record.hits < options.report_far_min_hits) {
    return false;
  }
  return record.pair_hits >= options.report_min_pair_hits &&
         (record.object_class == ObjectClass::kMoving ||
          record.person_hits >= options.report_min_person_share * record.hits);
}

bool ReportedAtBirth(const ObjectRecord& record, int64_t utime, const PeopleOptions& options) {
  return options.report_pair_births_confidence > 0.0 && !record.confirmed &&
         record.first_seen_utime == utime && record.last_seen_utime == utime &&
         record.kind == ObjectKind::kPerson &&
         record.birth_pair_confidence >= options.report_pair_births_confidence;
}

ObjectKind KindOfRecord(const ObjectRecord& record) {
  return 2 * record.person_hits > record.hits ? ObjectKind::kPerson : ObjectKind::kOther;
}

void RecordMeasurementKind(bool person_measurement, ObjectRecord* record) {
  if (person_measurement) ++record->person_hits;
  record->kind = KindOfRecord(*record);
}

double MaxSpeedOfKind(ObjectKind kind, const PeopleOptions& options) {
  return kind == ObjectKind::kPerson ? options.max_speed_mps : options.other_max_speed_mps;
}

int LimitSpeedsToTheirKind(const PeopleOptions& options, SlamState* state) {
  int limited = 0;
  for (int k = 0; k < state->num_objects(); ++k) {
    const StateObject& o = state->object(k);
    if (!o.has_velocity()) continue;
    const double max_speed = MaxSpeedOfKind(o.record.kind, options);
    const Eigen::Vector2d v = state->velocity(k);
    const double speed = v.norm();
    if (max_speed <= 0.0 || !(speed > max_speed)) continue;
    state->mean().segment<2>(o.velocity_index) = v * (max_speed / speed);
    ++limited;
  }
  return limited;
}

namespace {

// Whether an object whose record `counts` lies closer than radius_m to point_m (map frame).
template <class Counts>
bool AnObjectCloserThan(const Eigen::Vector2d& point_m, double radius_m, const SlamState& state,
                        Counts counts) {
  for (int k = 0; k < state.num_objects(); ++k) {
    if (!counts(state.object(k).record)) continue;
    if ((state.position(k) - point_m).norm() < radius_m) return true;
  }
  return false;
}

}  // namespace

bool TooCloseToAPerson(const Eigen::Vector2d& point_m, const PeopleOptions& options,
                       const SlamState& state) {
  if (!(options.min_separation_m > 0.0)) return false;
  return AnObjectCloserThan(point_m, options.min_separation_m, state,
                            [](const ObjectRecord& r) { return r.kind == ObjectKind::kPerson; });
}

bool BesideAPersonOrMover(const Eigen::Vector2d& point_m, const PeopleOptions& options,
                          const SlamState& state) {
  return AnObjectCloserThan(point_m, options.report_pair_births_clear_m, state,
                            [](const ObjectRecord& r) {
                              return r.kind == ObjectKind::kPerson ||
                                     r.object_class == ObjectClass::kMoving;
                            });
}

std::vector<int> PersonTracksTakenOver(const std::vector<uint8_t>& measured,
                                       const PeopleOptions& options, const SlamState& state) {
  std::vector<int> taken_over;
  if (!(options.taken_over_within_m > 0.0)) return taken_over;
  const auto is_person = [&](int k, ObjectClass object_class) {
    const ObjectRecord& r = state.object(k).record;
    return r.kind == ObjectKind::kPerson && r.object_class == object_class;
  };
  for (int j = 0; j < state.num_objects(); ++j) {
    if (measured[static_cast<size_t>(j)] || !is_person(j, ObjectClass::kStatic)) continue;
    for (int m = 0; m < state.num_objects(); ++m) {
      if (!measured[static_cast<size_t>(m)] || !is_person(m, ObjectClass::kMoving) ||
          !state.object(m).record.confirmed) {
        continue;
      }
      // Born where the standing track's measurements ended, not an old mover passing by.
      const double born_before_s = SecondsBetween(state.object(j).record.last_seen_utime,
                                                  state.object(m).record.first_seen_utime);
      if (born_before_s > options.taken_over_born_within_s) continue;
      if ((state.position(m) - state.position(j)).norm() <= options.taken_over_within_m) {
        taken_over.push_back(j);
        break;
      }
    }
  }
  return taken_over;
}

namespace {

// Whether the measurements of the last `window` scans went from one track to the other and back
// (bit 0 the newest scan; `a` and `b` never set together).
bool MeasuredInTurn(uint32_t a, uint32_t b, int window) {
  int owner = 0;  // 1: a, 2: b, 0: none yet
  int changes = 0;
  for (int bit = window - 1; bit >= 0; --bit) {
    const int now = (a >> bit) & 1u ? 1 : ((b >> bit) & 1u ? 2 : 0);
    if (now == 0) continue;
    if (owner != 0 && now != owner) ++changes;
    owner = now;
  }
  return changes >= 2;
}

}  // namespace

std::vector<int> PersonTracksMeasuredInTurn(const std::vector<uint8_t>& measured,
                                            const PeopleOptions& options, const SlamState& state) {
  std::vector<int> unmeasured;
  if (!(options.measured_in_turn_within_m > 0.0)) return unmeasured;
  const int window = options.measured_in_turn_window_scans;
  const uint32_t mask = window >= 32 ? ~0u : ((1u << window) - 1u);
  for (int j = 0; j < state.num_objects(); ++j) {
    const ObjectRecord& a = state.object(j).record;
    if (measured[static_cast<size_t>(j)] || a.kind != ObjectKind::kPerson ||
        (a.recent_scans & mask) != mask) {
      continue;
    }
    for (int m = 0; m < state.num_objects(); ++m) {
      const ObjectRecord& b = state.object(m).record;
      if (!measured[static_cast<size_t>(m)] || b.kind != ObjectKind::kPerson ||
          (b.recent_scans & mask) != mask) {
        continue;
      }
      const uint32_t hits_a = a.recent_hits & mask;
      const uint32_t hits_b = b.recent_hits & mask;
      if ((hits_a & hits_b) != 0u || !MeasuredInTurn(hits_a, hits_b, window)) continue;
      if ((state.position(m) - state.position(j)).norm() <= options.measured_in_turn_within_m) {
        unmeasured.push_back(j);
        break;
      }
    }
  }
  return unmeasured;
}

}  // namespace slammtt
