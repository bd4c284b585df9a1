// What one scan of the estimator did (ScanResult::counts, estimator.h): every step of
// Algorithm 2 adds its own counts.
#pragma once

#include <cstdint>

namespace slammtt {

// What one scan did.
struct StepCounts {
  int features = 0;             // received
  int features_rejected = 0;
  int features_at_edge_of_view = 0;  // cut by the edge of the field of view (R inflated)
  int level1_updates = 0;
  int level2_updates = 0;
  int level3_updates = 0;
  int manoeuvres = 0;           // movers given a velocity jump before level 3
  int hypotheses = 0;
  int new_objects = 0;
  int reacquired = 0;           // lost movers seen again (identity taken over, reacquisition.h)
  int objects_refused = 0;      // by the object cap
  int person_births_joined = 0;  // person features too near a person track to start one
  int person_tracks_taken_over = 0;  // standing person tracks a walker took over (people.h)
  int person_tracks_measured_in_turn = 0;  // person tracks one person moved between (people.h)
  int pruned = 0;
  int landmarks_archived = 0;   // left the state for the archive (landmark_window.h)
  int landmarks_restored = 0;   // came back from it
  int became_moving = 0;
  int became_static = 0;
  int started_moving = 0;
  int speeds_limited = 0;       // velocity estimates limited to their kind's speed (people.h)
  int updates_failed = 0;
  int static_updates_skipped = 0;  // associated objects left out by the per-scan budgets K, M
  int state_recovered = 0;      // 1: the scan ended non-finite and was recovered
  int features_over_cap = 0;    // beyond max_features_per_scan, dropped (the farthest)
  int64_t ransac_pair_tests = 0;  // hypotheses x evaluation pairs (ml_ransac.h)
  int ransac_budget_cut = 0;    // 1: RANSAC stopped at ransac_max_pair_tests
  int lines = 0;                // line features received
  int lines_rejected = 0;
  int line_updates = 0;         // line features that updated the state (levels 1 and 2)
  int lines_associated = 0;     // with a line landmark (updating or left out by the budget)
  int line_updates_skipped = 0;  // by the budget of line updates
  int new_lines = 0;
  int lines_refused = 0;        // by lines_max_landmarks
  int points_on_lines = 0;      // point features on a line landmark, not measurements
  int observation_predictions = 0;  // times every object's observation was predicted (once
                                    // per state the scan passed through)
};

}  // namespace slammtt
