// Manoeuvres, before level 3 (EstimatorOptions::manoeuvre_velocity_sigma_mps): a MOVING object
// that got no measurement from levels 1 and 2 while a free measurement lies inside its gate dn
// as it would be after a velocity jump gets that jump (ekf_prediction.h: AddVelocityJump, the
// covariance resetting of Bar-Shalom, Li and Kirubarajan 2001, section 11.2), so that level 3
// can take the measurement of a person who turned or stopped.
//
// The jump, of standard deviation sigma over the last predicted interval dt, adds (sigma dt)^2 I
// to the position covariance, so the gate is judged with H_p (sigma dt)^2 H_p^T added to
// H P H^T: a person who stops dead is outside the gate of the steady walk within a few scans,
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
