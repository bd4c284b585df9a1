// Step 1b of a scan (after the prediction, before the point features are gated): the scan's line
// features (walls, furniture sides) update the line landmarks of the state, and start new ones.
// A line is static structure: it is never a moving object, never tracked, never classified and
// never pruned; the point steps of Algorithm 2 do not see it. Because the lines update the
// robot pose first, the point features are gated at a pose that the walls have corrected.
//
// Per scan, with the landmarks' observations predicted once (line_model.h) and every
// feature-landmark pair judged by its normalised innovation squared (NIS, 2 dof) at the state
// the step starts from:
//  1. compatible pairs: NIS < gate_d1_chi2 (the points' gate d1) and the observed extents
//     overlap: the feature's end points, placed in the map by the predicted pose and projected
//     onto the landmark's line, reach within lines_extent_gap_m of the landmark's extent (two
//     collinear walls on either side of a corridor's opening stay two landmarks, the pieces of
//     one wall interrupted by a door of up to the gap become one);
//  2. level 1: pairs whose feature and landmark have no other compatible pair update the state
//     together (Algorithm 2 line 5-6's rule for the compatibility matrix J);
//  3. level 2: the other compatible pairs, judged again at the state level 1 left, one to one
//     by increasing NIS, gate d1 again (no RANSAC: a line never moves, so there is no static /
//     moving hypothesis to choose);
//  4. budget: of the landmarks with a compatible pair, only the lines_max_updates_per_scan
//     least recently updated (ties: lower index) update the state; the others are associated
//     (hits, extent) and leave the state alone (update_budget.h's rule for points): the dense
//     update costs O(n^2) per line;
//  5. extents: every associated landmark's extent grows to cover its feature's (at the updated
//     pose);
//  6. new landmarks: a feature in no pair, and outside gate new_object_gate_dn_chi2 of every
//     landmark whose extent it overlaps is a candidate line, kept outside the state until it
//     stays (line_candidates.h); then it becomes a landmark (line_model.h:
//     LineFromObservation of its latest feature, with its covariance from the robot's and the
//     feature's), up to lines_max_landmarks.
// Bad input: a feature with a non-finite value, rho < 0, alpha outside [-pi, pi], a negative
// variance or a covariance that is not positive semi-definite is rejected and counted; a
// feature or landmark seen edge on (predicted |rho| < kMinLineDistance_m) is not associated.
// The feature's covariance is floored at lines_min_rho_sigma_m / lines_min_alpha_sigma_deg:
// a least-squares fit's covariance (perception.md) knows only the range noise, not a slightly
// bent wall, a beam's footprint or the ends of a run cut by a door.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "common/options_schema.h"
#include "estimator/line_candidates.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"

namespace slammtt {

// One line_feature_t as received: Hessian normal form in the sensor frame and the observed
// extent's end points (sensor frame).
struct LineReading {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
  double rho_var_m2 = 0.0;
  double alpha_var_rad2 = 0.0;
  double rho_alpha_cov_m_rad = 0.0;
  Eigen::Vector2d first_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_m = Eigen::Vector2d::Zero();
};

struct LineLandmarkOptions {
  bool enabled = true;                       // false: line features are ignored (counted)
  double min_rho_sigma_m = 0.03;             // floor of a feature's rho sigma
  double min_alpha_sigma_rad = 1.0 * M_PI / 180.0;  // floor of its alpha sigma
  double extent_gap_m = 1.0;                 // the extents must overlap or lie closer
  int confirm_scans = 3;                     // scans a candidate is seen in to become a landmark
  double candidate_timeout_s = 0.5;          // a candidate unseen for longer is dropped
  double candidate_match_m = 0.1;            // a feature continues a candidate within these
  double candidate_match_rad = 2.0 * M_PI / 180.0;
  int max_updates_per_scan = 16;             // budget of line updates per scan (0: no limit)
  int max_landmarks = 400;                   // new lines beyond are refused (counted)
  // A point feature this close to a line landmark's line, within its seen extent lengthened by
  // point_end_margin_m at both ends, is a piece of that wall (a run too short for a line, a
  // corner, a door jamb: perception.md) and not a measurement of the point steps. 0: off.
  // 0.25 m rather than 0.1: door jambs and wall ends 0.1-0.2 m from a wall became movers;
  // office / corridor seeds 1-20 (held-out 21-30 alike) people MOTA median 0.639 -> 0.760 /
  // 0.195 -> 0.700, non-person movers 3.75 -> 2.0 / 5.0 -> 2.0 per minute (docs/targets.md).
  double point_on_line_m = 0.25;
  double point_end_margin_m = 0.2;
  // A point feature behind a line landmark (on the far side of its line from the sensor) by at
  // most this, the beam to it crossing the landmark's seen extent, is a piece of that wall too
  // (past a wall's end the laser does see behind it: no end margin): the laser does not see
  // through a wall, so the point is the wall's own short run whose fitted centre fell behind
  // its surface (a wall with dropouts broken into runs too short for a line). 0: off. The
  // corridor's far end (50 % dropouts): 58 of its 90 movers that are no person (seeds 1-20,
  // with odometry) sat 0.3-0.5 m behind its wall landmark (scripts/non-person-movers.py).
  double point_behind_line_m = 0.6;
};

void VisitLineLandmarkOptions(OptionVisitor* visitor, LineLandmarkOptions* options);

// What the step did in one scan.
struct LineStepCounts {
  int features = 0;         // received
  int rejected = 0;         // bad input
  int level1_updates = 0;
  int level2_updates = 0;
  int updates_skipped = 0;  // associated, left out by the budget
  int associated = 0;       // features associated with a landmark
  int new_landmarks = 0;
  int refused = 0;          // by lines_max_landmarks
  int candidates = 0;       // line candidates held after the scan
  int failed = 0;           // numerically unusable updates
  std::string first_rejection;
};

// Gates of the points' association (EstimatorOptions), passed in so that lines and points
// share them.
struct LineGates {
  double d1_chi2 = 9.21;
  double dn_chi2 = 20.0;
  int group_size = 32;
};

// Per measurement (range, bearing from the sensor, at the current pose): 1 when it lies on a
// line landmark or behind it (LineLandmarkOptions::point_on_line_m, point_behind_line_m,
// point_end_margin_m). All 0 when the step is disabled or both distances are 0.
std::vector<uint8_t> PointsOnLineLandmarks(const std::vector<Eigen::Vector2d>& range_bearings,
                                           const LineLandmarkOptions& options,
                                           const SensorMount& mount, const SlamState& state);

// Steps 1-6 above on one scan at `utime`. New landmarks take ids from *next_id; `candidates`
// holds the candidate lines from scan to scan (the caller keeps it, empty at the start).
LineStepCounts UpdateLineLandmarks(const std::vector<LineReading>& lines, int64_t utime,
                                   const LineLandmarkOptions& options, const LineGates& gates,
                                   const SensorMount& mount, int64_t* next_id, SlamState* state,
                                   std::vector<LineCandidate>* candidates);

}  // namespace slammtt
