// Life cycle of the estimator's objects (paper Algorithm 2, lines 11 and 13): creation of
// tentative objects, confirmation after enough hits (the track threshold T_th), and pruning of
// objects unseen for too long (paper section 5.1: 3.5 s).
//
// Pruning rules:
//   - a tentative object is dropped after tentative_prune_unseen_s without a measurement
//     (a false alarm must not live 3.5 s);
//   - a confirmed object with velocity states (moving or undecided) is dropped after
//     prune_unseen_s without a measurement, as in the paper;
//   - a static landmark is kept while out of view (the paper makes pruning static objects
//     optional; a map that forgets what the robot cannot see cannot close a loop), and dropped
//     after static_prune_unseen_in_view_s during which it was inside the sensor's field of
//     view and range and yet got no measurement (it was removed, or it was a person who
//     walked away). 0 disables it.
#pragma once

#include <cstdint>

#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

struct TrackManagementOptions {
  int confirm_hits = 3;                       // T_th
  double prune_unseen_s = 3.5;                // paper section 5.1
  double tentative_prune_unseen_s = 1.0;
  double static_prune_unseen_in_view_s = 3.5;
};

// A fresh record for an object first seen at utime.
ObjectRecord NewObjectRecord(int64_t id, int64_t utime, ObjectClass object_class);

// Marks a scan in which the object got a measurement.
void RecordHit(int64_t utime, const TrackManagementOptions& options, ObjectRecord* record);

// Accounts a scan of dt_s without a measurement (in_view: the object was inside the sensor's
// field of view and range).
void RecordMiss(double dt_s, bool in_view, ObjectRecord* record);

// Whether the object should be removed at utime.
bool ShouldPrune(const ObjectRecord& record, bool has_velocity, int64_t utime,
                 const TrackManagementOptions& options);

// Whether a map point lies inside the sensor's field of view (centred on the sensor's x axis,
// field_of_view_rad wide) and within max_range_m.
bool InFieldOfView(const Eigen::Vector3d& robot_pose, const Eigen::Vector2d& point,
                   const SensorMount& mount, double max_range_m, double field_of_view_rad);

}  // namespace slammtt
