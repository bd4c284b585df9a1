// Re-acquisition of lost movers. A confirmed MOVING track that is no longer reported
// (ReportedConfirmed, track_management.h: its person has not been seen for a while, typically
// out of the field of view) keeps coasting along its last velocity, but a person nobody watched
// may have turned any number of times: when they come back into view, their measurement lies
// outside every gate and starts a new object, which must then be confirmed and found moving
// again (about 0.5 s of misses) under a new identity. Instead, in two steps at two scans:
//  1. at the scan a measurement starts a new object (TagPossibleContinuations, after
//     classification, before the new objects are made): the measurement is tagged as the
//     possible continuation of a lost track when the person can have walked there since the
//     track was last seen: |point - last_seen_m| <= reacquire_speed_mps * unseen_s
//     (ChooseReacquisitions; pairs one-to-one in increasing distance over reach). A measurement
//     that a static landmark without a measurement this scan may have produced (within twice
//     the new-object gate of it: an error out in the tail) carries no identity. The new object
//     keeps the tag (ObjectRecord::continues_id);
//  2. at the new object's second measurement, a later scan that associates it through the
//     ordinary gates (TakeOverLostIdentities, after the hits and misses, before classification;
//     a lone outlier, e.g. a landmark's measurement out of its gate, never gets one): if that
//     track is still lost, the new object takes over its identity, first sighting and MOVING
//     label and is confirmed; the lost track is removed with the pruned objects. The new object
//     keeps its own state: its velocity comes from its own two measurements, not from the old
//     walk.
// Otherwise the new object lives on as any new object. Off with reacquire_speed_mps 0 and in
// baseline (a).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "estimator/association.h"
#include "estimator/track_management.h"

namespace slammtt {

struct LostTrack {
  int object = -1;
  Eigen::Vector2d last_seen_m = Eigen::Vector2d::Zero();
  double unseen_s = 0.0;
};
struct BirthPoint {
  int measurement = -1;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();  // map frame
};
struct Reacquisition {
  int measurement = -1;
  int object = -1;
};

// Whether object `object` is a lost mover at utime: confirmed MOVING with velocity states, not
// measured this scan (`unmeasured`), no longer reported.
bool IsLostMover(const StateObject& object, bool unmeasured, int64_t utime,
                 const TrackManagementOptions& options);

// Step 1's pairing of births with lost tracks.
std::vector<Reacquisition> ChooseReacquisitions(const std::vector<LostTrack>& lost,
                                                const std::vector<BirthPoint>& births,
                                                double reacquire_speed_mps);

// Step 1: per measurement, the id of the lost track the new object it starts may continue (0:
// none). `nearest_nis`: per measurement, its smallest NIS to any object (scan_gating.h); a
// measurement starts a new object when it is free and that NIS is at least gate dn.
// `taken_over`: lost tracks whose identity step 2 gave away this scan (not lost any more).
std::vector<int64_t> TagPossibleContinuations(const ScanAssociation& scan,
                                              const std::vector<double>& nearest_nis,
                                              const std::vector<int>& taken_over,
                                              const EstimatorOptions& options,
                                              ObservationPredictions* predicted,
                                              const SlamState& state,
                                              const Assignment& assignment);

// Step 2: the identity take-overs of this scan (counts->reacquired). Returns the lost tracks
// whose identity went to a new object, to be removed.
std::vector<int> TakeOverLostIdentities(int64_t utime, const EstimatorOptions& options,
                                        const Assignment& assignment, SlamState* state,
                                        StepCounts* counts);

}  // namespace slammtt
