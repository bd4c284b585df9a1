// Step 3 of Algorithm 2 (lines 3-4): every measurement of the scan against every object at the
// predicted state (gating.h: GatePairs), the compatibility matrix J and what later steps ask
// of the gating.
//
// Pairs are kept up to the widest gate any later step asks about: d1 (J, levels 1 and 2), d2
// (level 3, when on) and dn (new objects, the landmark tests of classification). J is the
// pairs under d1. For every measurement, the smallest NIS to any object: a measurement whose
// smallest NIS is at least dn starts a new object when nothing takes it.
#pragma once

#include <vector>

#include "estimator/association.h"
#include "estimator/estimator_options.h"
#include "estimator/gating.h"
#include "estimator/point_measurement.h"

namespace slammtt {

struct ScanGating {
  std::vector<Candidate> gated;       // NIS < max(d1, d2 if level 3, dn), by measurement, object
  std::vector<Candidate> compatible;  // J: the pairs of `gated` with NIS < d1, same order
  std::vector<double> nearest_nis;    // per measurement (+infinity: no object within the gates)
  // Per measurement, its smallest NIS to a held-back landmark within gate dn (+infinity: none);
  // already in nearest_nis (BlockBirthsInsideHeldBackGates).
  std::vector<double> held_back_nis;
};

// A re-entered landmark held back from association (observation_predictions.h:
// HoldBackUnsureReentries, its prediction marked held_back) still stands where it was mapped: a
// measurement inside its new-object gate dn may be that landmark, seen before it is surely inside
// the laser's range. Such a measurement starts no new object in this scan (its nearest NIS is
// lowered to the held-back landmark's; it is in no pair, so no step updates anything with it):
// it would be a second landmark for the same post, which the landmark takes again once it is
// judged (LandmarkWindowTest.OverALoopNoLandmarkIsLostOrMappedTwice: with the stationary anchor
// such duplicates became STATIC, 123 landmarks for 120 posts, and one wrong association between
// the duplicate and the re-entered landmark moved the robot by one post spacing, 4 m).
void BlockBirthsInsideHeldBackGates(const std::vector<PointMeasurement>& measurements,
                                    const std::vector<ObjectPrediction>& predictions,
                                    double new_object_gate_chi2, std::vector<double>* nearest_nis);

ScanGating GateScan(const std::vector<PointMeasurement>& measurements,
                    const std::vector<ObjectPrediction>& predictions,
                    const EstimatorOptions& options);

// Per measurement, the smallest NIS that decides whether it may start a new object (at least
// gate dn: it may), once the levels have associated: nearest_nis, or with
// new_object_gate_skips_claimed_objects the smallest NIS to the objects that took no
// measurement of their own in this scan, and to held-back landmarks. An object that took its
// own measurement is accounted for; another measurement inside its gate dn is a second thing
// beside it (two far landmarks a few metres apart have gates dn that overlap at the edge of the
// range), and kept from starting an object it would have no object at all: its measurements
// would pull the nearby object towards it instead (s1-crossing's false movers).
// A person (an object of kind PERSON, or one that took a person feature) and a MOVING object
// still block: the second leg of a person, taken alone as a point beside the paired person
// (people.h), is the same person, and so most likely is a second point inside a walker's gate
// (s1-crossing seed 15: two identity switches when MOVING objects did not block, none when
// they do), and so does any object whose own measured point is closer to the measurement than
// new_object_beside_claimed_min_separation_m. The two things this is for are landmarks, STATIC
// or not yet decided, metres apart.
std::vector<double> NearestNisForBirths(const std::vector<PointMeasurement>& measurements,
                                        const ScanGating& gating, const Assignment& assignment,
                                        const SlamState& state, const EstimatorOptions& options);

// The objects (indices at the assignment's state) that took their own measurement in this scan
// and have inside their gate dn a measurement that starts a new object by `birth_nis`
// (NearestNisForBirths) though it would not by nearest_nis: the objects a new object is born
// beside. Ascending, each once.
std::vector<int> ClaimedObjectsBesideBirths(const ScanGating& gating,
                                            const std::vector<double>& birth_nis,
                                            const Assignment& assignment, double dn_chi2);

}  // namespace slammtt
