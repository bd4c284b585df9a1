// Runs a PointWorld through the Estimator and measures what the tests assert: robot error,
// per-object classification delays, identity switches, map contents.
#pragma once

#include <map>
#include <random>
#include <string>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/testing/point_world.h"

namespace slammtt::testing {

struct ObjectHistory {
  bool mover = false;
  double first_seen_s = -1.0;         // first scan with a feature of it
  double first_moving_s = -1.0;       // first scan where its match is a confirmed MOVING track
  double first_static_s = -1.0;       // first scan where its match is STATIC
  double last_static_s = -1.0;        // last scan where its match is STATIC
  double last_moving_s = -1.0;
  int id_switches = 0;                // changes of the matched estimate's id while matched
  int64_t last_matched_id = 0;
  int scans_matched = 0;
  int scans_visible = 0;
};

struct RunSummary {
  double ate_rmse_m = 0.0;            // estimate vs truth (same frame: both start at the origin)
  double odometry_rmse_m = 0.0;       // dead reckoning vs truth
  double max_position_error_m = 0.0;
  std::map<int64_t, ObjectHistory> objects;  // by truth id
  int movers_in_final_map = 0;        // final STATIC objects within match distance of a mover
  int static_labelled_static = 0;     // truth-static objects matched by a STATIC estimate at end
  int static_total = 0;
  int64_t hypotheses = 0;
  ScanResult last;
  EstimatorCounters counters;
};

// Runs `scans` scans. An estimate matches a truth object when it is the nearest within
// match_m of it.
RunSummary RunScenario(PointWorld* world, Estimator* estimator, int scans, uint64_t seed,
                       double match_m = 1.0);

std::string Describe(const RunSummary& summary);

}  // namespace slammtt::testing
