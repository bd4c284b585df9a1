#include "estimator/track_management.h"

#include <cmath>

namespace slammtt {

ObjectRecord NewObjectRecord(int64_t id, int64_t utime, ObjectClass object_class) {
  ObjectRecord record;
  record.id = id;
  record.object_class = object_class;
  record.first_seen_utime = utime;
  record.last_seen_utime = utime;
  record.class_change_utime = utime;
  record.hits = 1;
  return record;
}

void RecordHit(int64_t utime, const TrackManagementOptions& options, ObjectRecord* record) {
  ++record->hits;
  record->last_seen_utime = utime;
  record->unseen_in_view_s = 0.0;
  if (record->hits >= options.confirm_hits) record->confirmed = true;
}

void RecordMiss(double dt_s, bool in_view, ObjectRecord* record) {
  if (in_view) record->unseen_in_view_s += dt_s;
}

bool ShouldPrune(const ObjectRecord& record, bool has_velocity, int64_t utime,
                 const TrackManagementOptions& options) {
  const double unseen_s = 1e-6 * static_cast<double>(utime - record.last_seen_utime);
  if (!record.confirmed) return unseen_s > options.tentative_prune_unseen_s;
  if (has_velocity) return unseen_s > options.prune_unseen_s;
  return options.static_prune_unseen_in_view_s > 0.0 &&
         record.unseen_in_view_s > options.static_prune_unseen_in_view_s;
}

bool InFieldOfView(const Eigen::Vector3d& robot_pose, const Eigen::Vector2d& point,
                   const SensorMount& mount, double max_range_m, double field_of_view_rad) {
  const Eigen::Vector2d z = PredictRangeBearing(robot_pose, point, mount);
  if (!(z(0) <= max_range_m)) return false;
  return std::abs(z(1)) <= 0.5 * field_of_view_rad;
}

}  // namespace slammtt
