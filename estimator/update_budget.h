// The per-scan budget of static-landmark updates (EstimatorOptions::max_static_updates_per_scan,
// K): which objects may update the state this scan.
//
// Every object with velocity states (moving, undecided) may. Of the static landmarks that have a
// candidate pair this scan (a pair in `gated`), the K least recently updated may (ties: lower
// object index); the others are still associated (hits, misses, classification and new objects
// see every association) but leave the state alone. The choice reads the state's book-keeping
// only (ObjectRecord::last_update_utime), never the measurements' values, so leaving the others
// out keeps the filter consistent: it only gives up information. The dense update costs O(n^2)
// per observation; this bounds the cost of a scan that sees hundreds of landmarks
// (docs/estimator.md, "Speed"). K <= 0: no limit.
//
// Objects with velocity states have a budget of their own, M
// (EstimatorOptions::max_mover_updates_per_scan): of those with a candidate pair, the M least
// recently updated may update, chosen the same way. It binds only in a scene no real scene is
// (hundreds of undecided objects made by a hostile FEATURES message: 477 updates of a 2 004-state
// covariance took 2 s in one scan), and bounds the cost of a scan with max_objects: at most
// K + M dense updates. M <= 0: no limit.
#pragma once

#include <cstdint>
#include <vector>

#include "estimator/gating.h"
#include "estimator/slam_state.h"

namespace slammtt {

// Per object index: 1 when it may update the state this scan.
std::vector<uint8_t> ObjectsThatMayUpdate(const SlamState& state,
                                          const std::vector<Candidate>& gated, int budget,
                                          int mover_budget);

}  // namespace slammtt
