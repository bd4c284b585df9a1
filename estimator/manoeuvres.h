// Manoeuvres, before level 3 (EstimatorOptions::manoeuvre_velocity_sigma_mps): a MOVING object
// that got no measurement from levels 1 and 2 gets a velocity jump (ekf_prediction.h:
// AddVelocityJump, the covariance resetting of Bar-Shalom, Li and Kirubarajan 2001, section
// 11.2) when that jump is what lets level 3 take the measurement of a person who turned or
// stopped: a free measurement lies inside its gate d2 as it would be after the jump, and no
// free measurement lies inside its gate d2 as it is (level 3 takes that one without a jump).
// Without the second condition a mover far away, whose measurement missed gate d1 by its
// noise, had its velocity thrown away and was pulled onto whatever lay nearby (on s1-crossing
// seeds 1-30 the s1 targets held on 12 seeds with it, 17 without: docs/targets.md).
//
// The jump, of standard deviation sigma over the last predicted interval dt, adds (sigma dt)^2 I
// to the position covariance, so the widened gate is judged with H_p (sigma dt)^2 H_p^T added
// to H P H^T: a person who stops dead is outside the gate of the steady walk within a few scans,
// inside the manoeuvre's. Undecided objects are left alone (they still have their wide velocity
// prior). Off when sigma or dt is 0.
#pragma once

#include "estimator/association.h"

namespace slammtt {

// Gives the jumps (counts->manoeuvres). `dt_s`: the scan's predicted interval.
void GiveManoeuvringMoversAVelocityJump(double dt_s, const ScanAssociation& scan,
                                        const EstimatorOptions& options,
                                        ObservationPredictions* predicted, SlamState* state,
                                        const Assignment& assignment, StepCounts* counts);

}  // namespace slammtt
