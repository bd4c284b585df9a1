#include "estimator/people.h"

namespace slammtt {

void VisitPeopleOptions(OptionVisitor* v, PeopleOptions* o) {
  using R = OptionRange;
  v->Double("acceleration_sigma_mps2", &o->acceleration_sigma_mps2, R::AtLeast(0),
            "process noise sigma_Q (eq. 8) of MOVING people");
  v->Double("max_speed_mps", &o->max_speed_mps, R::AtLeast(0),
            "speed gate of people: faster estimates are limited (0: off)");
  v->Double("other_max_speed_mps", &o->other_max_speed_mps, R::AtLeast(0),
            "speed gate of every other mover (0: off)");
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

}  // namespace slammtt
