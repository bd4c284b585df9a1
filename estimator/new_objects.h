// New objects (paper Algorithm 2, line 13): every measurement that no level took and whose NIS
// to every object is at least gate dn starts an object, at the point the inverse of eq. 10
// gives from the robot's pose, with its cross-covariance with the robot (SlamState::AddObject).
// A new object is UNDECIDED and tentative, of the kind of its measurement (people.h), with zero
// velocity and velocity covariance
// new_object_velocity_sigma_mps^2 I, its "still" window open, and the lost track it may continue
// (reacquisition.h). In baseline (a), the static world, it is a STATIC landmark without
// velocity states, confirmed at once (plain EKF-SLAM maps a landmark at its first sighting).
// At most max_objects objects: the measurements beyond are refused and counted.
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

// Per measurement, the smallest NIS (from `gated`, scan_gating.h) to an object that could have
// produced it: one left without a measurement by the association. An object gives at most one
// point measurement per scan (the association's one-to-one rule), so one that took its own
// cannot be the source of a second: a second measurement near it is another object. Two
// landmarks 3 m apart at the 30 m edge of the range (6 degrees, three bearing sigmas) are
// both inside the new-object gate of the first one's wide new object; counted by every object,
// the second landmark's measurements never start an object of their own, and the first
// object, taking one then the other, seems to move (s1-crossing, landmarks 60 and 61 at 20 s).
// In baseline (a), the static world, every object counts (plain nearest-neighbour EKF-SLAM).
// +infinity where no object is near.
std::vector<double> NearestNisOfPossibleSources(const std::vector<Candidate>& gated,
                                                const EstimatorOptions& options,
                                                const Assignment& assignment);

// Adds the new objects with ids from *next_id on (counts->new_objects, objects_refused).
// `nearest_nis`: per measurement (NearestNisOfPossibleSources); `continues_id`: per measurement, the lost
// track's id it may continue (0: none). Returns the sightings that started objects that may be
// point landmarks (MayBePointLandmark, not a person feature), in measurement order, tentative
// unless the object starts as a confirmed static landmark (the static world).
std::vector<StaticObservation> AddNewObjects(const ScanAssociation& scan,
                                             const std::vector<double>& nearest_nis,
                                             const std::vector<int64_t>& continues_id,
                                             const EstimatorOptions& options,
                                             const Assignment& assignment, int64_t* next_id,
                                             SlamState* state, StepCounts* counts);

}  // namespace slammtt
