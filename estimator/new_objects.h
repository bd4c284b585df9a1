// New objects (paper Algorithm 2, line 13): every measurement that no level took and whose NIS
// to every object is at least gate dn starts an object, at the point the inverse of eq. 10
// gives from the robot's pose, with its cross-covariance with the robot (SlamState::AddObject).
// A new object is UNDECIDED and tentative, of the kind of its measurement (people.h), with zero
// velocity and velocity covariance
// new_object_velocity_sigma_mps^2 I, its "still" window open, and the lost track it may continue
// (reacquisition.h). In baseline (a), the static world, it is a STATIC landmark without
// velocity states, confirmed at once (plain EKF-SLAM maps a landmark at its first sighting).
// At most max_objects objects: the measurements beyond are refused and counted. A person
// feature closer than people_min_separation_m to an object of kind PERSON starts none (people.h).
//
// The measurement that starts an object is its first sighting: the filter placed the object
// there from the robot's pose of this scan, so the smoother needs it as well (smoother_input.h).
// Without it, the landmarks first seen in one scan share no measurement with that scan's pose,
// and the smoothed map can turn about it by the error of the next odometry increments.
#pragma once

#include <cstdint>
#include <vector>

#include "estimator/association.h"
#include "estimator/static_observations.h"

namespace slammtt {

// Adds the new objects with ids from *next_id on (counts->new_objects, objects_refused,
// person_births_joined).
// `nearest_nis`: per measurement (scan_gating.h); `continues_id`: per measurement, the lost
// track's id it may continue (0: none). Returns the sightings that started objects that may be
// point landmarks (MayBePointLandmark, not a person feature), in measurement order, tentative
// unless the object starts as a confirmed static landmark (the static world).
std::vector<StaticObservation> AddNewObjects(const ScanAssociation& scan,
                                             const std::vector<double>& nearest_nis,
                                             const std::vector<int64_t>& continues_id,
                                             const EstimatorOptions& options,
                                             const Assignment& assignment, int64_t* next_id,
                                             SlamState* state, StepCounts* counts);

// An UNDECIDED object beside which a new object is born in this scan (scan_gating.h:
// ClaimedObjectsBesideBirths; `objects`: their indices) has its moving evidence restarted: until
// now the measurements of the thing beside it, with no object of their own, pulled it between
// the two, so the velocity it gained says nothing of its own motion and would make a still
// landmark a false MOVING track. From now on each of the two has its own measurements.
// With new_object_beside_claimed_restarts_state its state is started again too, from the
// measurement it took in this scan, as a new object would be (AddNewObjects: the point of that
// measurement, the new-object covariance and velocity prior), keeping its identity and record.
// The position and velocity it had were a summary of the two things' measurements: they put it
// between the two, with a position covariance grown small on measurements of both. Kept, the
// object walks from there to its own thing over the next scans as a velocity, which becomes
// moving evidence once the restart is a few scans old (s1-crossing seed 3: posts 3 m apart at
// the 30 m edge of the range, one seen just inside it and one just beyond; docs/targets.md).
// Returns how many were restarted.
int RestartObjectsBesideBirths(const std::vector<int>& objects, const ScanAssociation& scan,
                               const Assignment& assignment, const EstimatorOptions& options,
                               SlamState* state);

}  // namespace slammtt
