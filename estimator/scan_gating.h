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

#include "estimator/estimator_options.h"
#include "estimator/gating.h"
#include "estimator/point_measurement.h"

namespace slammtt {

struct ScanGating {
  std::vector<Candidate> gated;       // NIS < max(d1, d2 if level 3, dn), by measurement, object
  std::vector<Candidate> compatible;  // J: the pairs of `gated` with NIS < d1, same order
  std::vector<double> nearest_nis;    // per measurement (+infinity: no object within the gates)
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

}  // namespace slammtt
