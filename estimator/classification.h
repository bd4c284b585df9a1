// Classification (paper Algorithm 2, line 12): every object held before the scan's new objects
// is judged static or moving from its estimate, with hysteresis, in both directions
// (motion_classifier.h), and the state follows the class.
//
//  - An object with velocity states is judged by ClassifyMover on its position and velocity
//    estimates. UNDECIDED -> MOVING changes the record only; -> STATIC conditions the whole
//    state on v = 0 and removes the velocity states (SlamState::RemoveVelocityAssumingZero).
//  - A static landmark is judged by ClassifyLandmark on the measurement that speaks about it:
//    its own, or else the unassigned measurement with the smallest NIS inside its gate dn,
//    mapped to the map frame with the prediction at the state after the updates. STATIC ->
//    UNDECIDED gives it velocity states again (zero mean, new_object_velocity_sigma_mps^2 I)
//    and opens a new "still" window.
// Baseline (a), the static world, classifies nothing.
#pragma once

#include <vector>

#include "estimator/association.h"

namespace slammtt {

// Per object: the measurement that speaks about each static landmark (-1: none; objects with
// velocity states: -1). `gated`: the scan's pairs (scan_gating.h), with their NIS at gating.
std::vector<int> LandmarkMeasurements(const std::vector<Candidate>& gated,
                                      const EstimatorOptions& options, const SlamState& state,
                                      const Assignment& assignment);

// Classifies every object (counts->became_moving, became_static, started_moving).
// `after_updates`: the predictions at the state after the updates (before this step).
void ClassifyObjects(const ScanAssociation& scan, const std::vector<Candidate>& gated,
                     const EstimatorOptions& options,
                     const std::vector<ObjectPrediction>& after_updates,
                     const Assignment& assignment, SlamState* state, StepCounts* counts);

}  // namespace slammtt
