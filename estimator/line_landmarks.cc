#include "estimator/line_landmarks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "estimator/angle.h"
#include "estimator/ekf_update.h"
#include "estimator/line_model.h"

namespace slammtt {
namespace {

// A validated line feature: its observation (rho, alpha), floored covariance and extent.
struct LineMeasurement {
  Eigen::Vector2d observation = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  Eigen::Vector2d first_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_m = Eigen::Vector2d::Zero();
};

// A landmark's predicted observation at the current state.
struct LinePrediction {
  bool usable = false;  // not seen edge on
  Eigen::Vector2d observation = Eigen::Vector2d::Zero();
  Eigen::Matrix<double, 2, 3> h_robot;
  Eigen::Matrix2d h_line;
  Eigen::Matrix2d hph;  // H P H^T
};

struct LinePair {
  int feature = -1;
  int line = -1;
  double nis = 0.0;
};

std::string CheckReading(const LineReading& r) {
  const double values[] = {r.rho_m,          r.alpha_rad,  r.rho_var_m2,  r.alpha_var_rad2,
                           r.rho_alpha_cov_m_rad, r.first_m(0), r.first_m(1), r.last_m(0),
                           r.last_m(1)};
  for (double v : values) {
    if (!std::isfinite(v)) return "a line feature has a non-finite value";
  }
  if (r.rho_m < 0.0) return "a line feature has rho_m < 0";
  if (std::abs(r.alpha_rad) > M_PI) return "a line feature's alpha_rad is outside [-pi, pi]";
  if (r.rho_var_m2 < 0.0 || r.alpha_var_rad2 < 0.0 ||
      r.rho_alpha_cov_m_rad * r.rho_alpha_cov_m_rad > r.rho_var_m2 * r.alpha_var_rad2) {
    return "a line feature's covariance is not positive semi-definite";
  }
  return "";
}

std::vector<LineMeasurement> ValidateLines(const std::vector<LineReading>& lines,
                                           const LineLandmarkOptions& options,
                                           LineStepCounts* counts) {
  std::vector<LineMeasurement> measurements;
  measurements.reserve(lines.size());
  const double min_rho_var = options.min_rho_sigma_m * options.min_rho_sigma_m;
  const double min_alpha_var = options.min_alpha_sigma_rad * options.min_alpha_sigma_rad;
  for (const LineReading& r : lines) {
    const std::string problem = CheckReading(r);
    if (!problem.empty()) {
      if (counts->rejected++ == 0) counts->first_rejection = problem;
      continue;
    }
    LineMeasurement m;
    m.observation = Eigen::Vector2d(r.rho_m, WrapAngle(r.alpha_rad));
    // Flooring the variances keeps the covariance positive semi-definite (its determinant only
    // grows).
    m.covariance << std::max(r.rho_var_m2, min_rho_var), r.rho_alpha_cov_m_rad,
        r.rho_alpha_cov_m_rad, std::max(r.alpha_var_rad2, min_alpha_var);
    m.first_m = r.first_m;
    m.last_m = r.last_m;
    measurements.push_back(m);
  }
  return measurements;
}

std::vector<LinePrediction> PredictLines(const SlamState& state, const SensorMount& mount) {
  std::vector<LinePrediction> predictions(static_cast<size_t>(state.num_lines()));
  const Eigen::Vector3d robot = state.robot_pose();
  const auto cov = state.covariance();
  for (int j = 0; j < state.num_lines(); ++j) {
    LinePrediction& p = predictions[static_cast<size_t>(j)];
    p.observation =
        PredictLineObservation(robot, state.line_params(j), mount, &p.h_robot, &p.h_line);
    p.usable = p.observation(0) >= kMinLineDistance_m;
    if (!p.usable) continue;
    const int l = state.line(j).param_index;
    const Eigen::Matrix2d cross = p.h_robot * cov.block<3, 2>(0, l) * p.h_line.transpose();
    p.hph = p.h_robot * cov.topLeftCorner<3, 3>() * p.h_robot.transpose() +
            p.h_line * cov.block<2, 2>(l, l) * p.h_line.transpose() + cross + cross.transpose();
  }
  return predictions;
}

Eigen::Vector2d Innovation(const LineMeasurement& m, const LinePrediction& p) {
  Eigen::Vector2d v = m.observation - p.observation;
  v(1) = WrapAngle(v(1));
  return v;
}

double Nis(const LineMeasurement& m, const LinePrediction& p) {
  const Eigen::Vector2d v = Innovation(m, p);
  const Eigen::Matrix2d s = p.hph + m.covariance;
  const double det = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  if (!(det > 0.0) || !(s(0, 0) > 0.0)) return std::numeric_limits<double>::infinity();
  // v^T S^-1 v with the 2x2 inverse written out.
  return (s(1, 1) * v(0) * v(0) - 2.0 * s(0, 1) * v(0) * v(1) + s(0, 0) * v(1) * v(1)) / det;
}

// A feature's end points, placed in the map by `robot`, in coordinates along `line` (map
// frame): the stretch of that line the feature shows.
struct Extent {
  double from_m = 0.0;
  double to_m = 0.0;
};

Extent ExtentAlong(const Eigen::Vector2d& line, const Eigen::Vector3d& robot,
                   const SensorMount& mount, const LineMeasurement& m) {
  const double a = PositionAlongLine(line, SensorPointToMap(robot, mount, m.first_m));
  const double b = PositionAlongLine(line, SensorPointToMap(robot, mount, m.last_m));
  return {std::min(a, b), std::max(a, b)};
}

// Whether the feature's extent (placed by the current pose) reaches within `gap_m` of line j's.
bool ExtentsOverlap(const SlamState& state, const SensorMount& mount, const LineMeasurement& m,
                    int j, double gap_m) {
  const Extent seen = ExtentAlong(state.line_params(j), state.robot_pose(), mount, m);
  const LineRecord& record = state.line(j).record;
  return seen.from_m <= record.extent_to_m + gap_m && seen.to_m >= record.extent_from_m - gap_m;
}

// What the steps of one scan share.
struct LineScan {
  const std::vector<LineMeasurement>& measurements;  // the valid features
  const LineLandmarkOptions& options;
  const LineGates& gates;
  const SensorMount& mount;
  int64_t utime = 0;

  int num_features() const { return static_cast<int>(measurements.size()); }
};

// Step 1 at the state the step starts from.
struct LineGating {
  std::vector<LinePair> compatible;   // NIS < d1, extents overlapping; by feature, then line
  std::vector<uint8_t> near_landmark;  // per feature: inside gate dn of a landmark it overlaps
};

LineGating GateLines(const LineScan& scan, const std::vector<LinePrediction>& predictions,
                     const SlamState& state) {
  LineGating gating;
  gating.near_landmark.assign(scan.measurements.size(), 0);
  for (int i = 0; i < scan.num_features(); ++i) {
    const LineMeasurement& m = scan.measurements[static_cast<size_t>(i)];
    for (int j = 0; j < state.num_lines(); ++j) {
      const LinePrediction& p = predictions[static_cast<size_t>(j)];
      if (!p.usable) continue;
      const double nis = Nis(m, p);
      if (!(nis < scan.gates.dn_chi2 || nis < scan.gates.d1_chi2)) continue;
      if (!ExtentsOverlap(state, scan.mount, m, j, scan.options.extent_gap_m)) continue;
      gating.near_landmark[static_cast<size_t>(i)] = 1;
      if (nis < scan.gates.d1_chi2) gating.compatible.push_back({i, j, nis});
    }
  }
  return gating;
}

// Level 1: the pairs whose feature and line appear in no other pair.
std::vector<LinePair> UniquePairs(const std::vector<LinePair>& pairs, int num_features,
                                  int num_lines) {
  std::vector<int> per_feature(static_cast<size_t>(num_features), 0);
  std::vector<int> per_line(static_cast<size_t>(num_lines), 0);
  for (const LinePair& p : pairs) {
    ++per_feature[static_cast<size_t>(p.feature)];
    ++per_line[static_cast<size_t>(p.line)];
  }
  std::vector<LinePair> unique;
  for (const LinePair& p : pairs) {
    if (per_feature[static_cast<size_t>(p.feature)] == 1 &&
        per_line[static_cast<size_t>(p.line)] == 1) {
      unique.push_back(p);
    }
  }
  return unique;
}

// Lines with a compatible pair that the budget lets update (1), of every line index.
std::vector<uint8_t> LinesThatMayUpdate(const SlamState& state,
                                        const std::vector<LinePair>& pairs, int budget) {
  std::vector<uint8_t> may_update(static_cast<size_t>(state.num_lines()), 1);
  if (budget <= 0) return may_update;
  std::vector<uint8_t> listed(may_update.size(), 0);
  std::vector<int> candidates;
  for (const LinePair& p : pairs) {
    if (listed[static_cast<size_t>(p.line)]) continue;
    listed[static_cast<size_t>(p.line)] = 1;
    candidates.push_back(p.line);
  }
  if (static_cast<int>(candidates.size()) <= budget) return may_update;
  auto staler = [&state](int a, int b) {
    const int64_t ta = state.line(a).record.last_update_utime;
    const int64_t tb = state.line(b).record.last_update_utime;
    return ta != tb ? ta < tb : a < b;
  };
  std::nth_element(candidates.begin(), candidates.begin() + budget, candidates.end(), staler);
  for (size_t k = static_cast<size_t>(budget); k < candidates.size(); ++k) {
    may_update[static_cast<size_t>(candidates[k])] = 0;
  }
  return may_update;
}

// Updates the state with `pairs` in groups, each linearised at the state the previous group
// left and re-gated there with `gate_chi2`; every line's alpha wrapped after. Returns the pairs
// applied.
int ApplyLinePairs(const std::vector<LinePair>& pairs,
                   const std::vector<LineMeasurement>& measurements, const SensorMount& mount,
                   double gate_chi2, int group_size, SlamState* state, LineStepCounts* counts) {
  int applied = 0;
  const size_t group = static_cast<size_t>(std::max(1, group_size));
  std::vector<LinearisedObservation> linearised;
  for (size_t begin = 0; begin < pairs.size(); begin += group) {
    const size_t end = std::min(pairs.size(), begin + group);
    const std::vector<LinePrediction> predictions = PredictLines(*state, mount);
    linearised.clear();
    for (size_t k = begin; k < end; ++k) {
      const LineMeasurement& m = measurements[static_cast<size_t>(pairs[k].feature)];
      const LinePrediction& p = predictions[static_cast<size_t>(pairs[k].line)];
      if (!p.usable || !(Nis(m, p) < gate_chi2)) continue;
      LinearisedObservation o;
      o.position_index = state->line(pairs[k].line).param_index;
      o.innovation = Innovation(m, p);
      o.h_robot = p.h_robot;
      o.h_position = p.h_line;
      o.r = m.covariance;
      linearised.push_back(o);
    }
    if (linearised.empty()) continue;
    if (!ApplyLinearisedGroup(linearised, state)) {
      counts->failed += static_cast<int>(linearised.size());
      continue;
    }
    applied += static_cast<int>(linearised.size());
    auto mean = state->mean();
    for (const StateLine& l : state->lines()) {
      mean(l.param_index + 1) = WrapAngle(mean(l.param_index + 1));
    }
  }
  return applied;
}


// The feature's extent, placed by the current pose, along line j.
void GrowExtent(const LineMeasurement& m, const SensorMount& mount, int j, SlamState* state) {
  const Extent seen = ExtentAlong(state->line_params(j), state->robot_pose(), mount, m);
  LineRecord& record = state->line(j).record;
  record.extent_from_m = std::min(record.extent_from_m, seen.from_m);
  record.extent_to_m = std::max(record.extent_to_m, seen.to_m);
}

// The feature as a map-frame line at the current pose, with its extent along it.
LineCandidate CandidateOf(const LineMeasurement& m, const SensorMount& mount, int64_t utime,
                          const SlamState& state) {
  const Eigen::Vector3d robot = state.robot_pose();
  LineCandidate c;
  c.line = LineFromObservation(robot, m.observation, mount);
  const Extent seen = ExtentAlong(c.line, robot, mount, m);
  c.extent_from_m = seen.from_m;
  c.extent_to_m = seen.to_m;
  c.scans = 1;
  c.first_seen_utime = utime;
  c.last_seen_utime = utime;
  return c;
}

void AddLineLandmark(const LineMeasurement& m, const SensorMount& mount, int64_t utime,
                     int64_t* next_id, SlamState* state) {
  const Eigen::Vector3d robot = state->robot_pose();
  Eigen::Matrix<double, 2, 3> g;
  Eigen::Matrix2d j_observation;
  const Eigen::Vector2d line = LineFromObservation(robot, m.observation, mount, &g,
                                                   &j_observation);
  LineRecord record;
  record.id = (*next_id)++;
  record.hits = 1;
  record.first_seen_utime = utime;
  record.last_seen_utime = utime;
  record.last_update_utime = utime;
  const Extent seen = ExtentAlong(line, robot, mount, m);
  record.extent_from_m = seen.from_m;
  record.extent_to_m = seen.to_m;
  state->AddLine(line, g, j_observation * m.covariance * j_observation.transpose(), record);
}

// Which landmark each feature of the scan got (steps 2-3), and which landmarks the budget lets
// update the state (step 4).
class LineAssociation {
 public:
  LineAssociation(int num_features, std::vector<uint8_t> may_update)
      : line_of_feature_(static_cast<size_t>(num_features), -1),
        line_taken_(may_update.size(), 0),
        may_update_(std::move(may_update)) {}

  // -1: none.
  int LineOf(int feature) const { return line_of_feature_[static_cast<size_t>(feature)]; }
  bool MayUpdate(int line) const { return may_update_[static_cast<size_t>(line)] != 0; }
  bool PairFree(const LinePair& p) const {
    return LineOf(p.feature) < 0 && !line_taken_[static_cast<size_t>(p.line)];
  }
  // Associates the pair; it joins `updating` when its landmark may update, and is counted as a
  // skipped update when not.
  void Associate(const LinePair& p, std::vector<LinePair>* updating, LineStepCounts* counts) {
    line_of_feature_[static_cast<size_t>(p.feature)] = p.line;
    line_taken_[static_cast<size_t>(p.line)] = 1;
    if (MayUpdate(p.line)) {
      updating->push_back(p);
    } else {
      ++counts->updates_skipped;
    }
  }

 private:
  std::vector<int> line_of_feature_;
  std::vector<uint8_t> line_taken_;
  std::vector<uint8_t> may_update_;
};

// Step 2: the pairs whose feature and landmark are in no other pair update the state together
// (the compatibility matrix settles them: no gate again). Returns the updates applied.
int AssociateLinesLevel1(const std::vector<LinePair>& compatible, const LineScan& scan,
                         LineAssociation* association, SlamState* state,
                         LineStepCounts* counts) {
  std::vector<LinePair> level1;
  for (const LinePair& p : UniquePairs(compatible, scan.num_features(), state->num_lines())) {
    association->Associate(p, &level1, counts);
  }
  return ApplyLinePairs(level1, scan.measurements, scan.mount,
                        std::numeric_limits<double>::infinity(), scan.gates.group_size, state,
                        counts);
}

// Step 3: the free compatible pairs, judged again at the state level 1 left, one to one by
// increasing NIS, gate d1. Returns the updates applied.
int AssociateLinesLevel2(const std::vector<LinePair>& compatible, const LineScan& scan,
                         LineAssociation* association, SlamState* state,
                         LineStepCounts* counts) {
  const std::vector<LinePrediction> after_level1 = PredictLines(*state, scan.mount);
  std::vector<LinePair> rest;
  for (LinePair p : compatible) {
    if (!association->PairFree(p)) continue;
    const LinePrediction& prediction = after_level1[static_cast<size_t>(p.line)];
    if (!prediction.usable) continue;
    p.nis = Nis(scan.measurements[static_cast<size_t>(p.feature)], prediction);
    if (p.nis < scan.gates.d1_chi2) rest.push_back(p);
  }
  std::stable_sort(rest.begin(), rest.end(),
                   [](const LinePair& a, const LinePair& b) { return a.nis < b.nis; });
  std::vector<LinePair> level2;
  for (const LinePair& p : rest) {
    if (association->PairFree(p)) association->Associate(p, &level2, counts);
  }
  return ApplyLinePairs(level2, scan.measurements, scan.mount, scan.gates.d1_chi2,
                        scan.gates.group_size, state, counts);
}

// Step 5: every associated landmark's extent grows to cover its feature's (at the updated
// pose); its record counts the hit, and the update when the budget let it update.
void RecordAssociatedLines(const LineScan& scan, const LineAssociation& association,
                           SlamState* state, LineStepCounts* counts) {
  for (int i = 0; i < scan.num_features(); ++i) {
    const int j = association.LineOf(i);
    if (j < 0) continue;
    ++counts->associated;
    GrowExtent(scan.measurements[static_cast<size_t>(i)], scan.mount, j, state);
    LineRecord& record = state->line(j).record;
    ++record.hits;
    record.last_seen_utime = scan.utime;
    if (association.MayUpdate(j)) record.last_update_utime = scan.utime;
  }
}

// Step 6: the features in no pair and near no landmark are sightings of candidate lines
// (line_candidates.h); a candidate seen often enough becomes a landmark, up to max_landmarks.
void AddConfirmedLines(const LineScan& scan, const LineAssociation& association,
                       const std::vector<uint8_t>& near_landmark, int64_t* next_id,
                       SlamState* state, std::vector<LineCandidate>* candidates,
                       LineStepCounts* counts) {
  for (int i = 0; i < scan.num_features(); ++i) {
    const LineMeasurement& m = scan.measurements[static_cast<size_t>(i)];
    if (association.LineOf(i) >= 0 || near_landmark[static_cast<size_t>(i)] ||
        m.observation(0) < kMinLineDistance_m) {
      continue;
    }
    const LineCandidate seen = CandidateOf(m, scan.mount, scan.utime, *state);
    if (!ConfirmLineCandidate(seen, scan.options, candidates)) continue;
    if (state->num_lines() >= scan.options.max_landmarks) {
      ++counts->refused;
      continue;
    }
    AddLineLandmark(m, scan.mount, scan.utime, next_id, state);
    ++counts->new_landmarks;
  }
}

}  // namespace


void VisitLineLandmarkOptions(OptionVisitor* v, LineLandmarkOptions* o) {
  using R = OptionRange;
  v->Bool("enabled", &o->enabled, "line features update line landmarks (walls) of the state");
  v->Double("min_rho_sigma_m", &o->min_rho_sigma_m, R::AtLeast(0),
            "floor of a line feature's rho sigma");
  v->Double("min_alpha_sigma_rad", &o->min_alpha_sigma_rad, R::AtLeast(0),
            "floor of a line feature's alpha sigma", OptionUnit::kDegrees);
  v->Double("extent_gap_m", &o->extent_gap_m, R::AtLeast(0),
            "a line feature and a landmark are associated only if their extents come closer");
  v->Double("point_on_line_m", &o->point_on_line_m, R::AtLeast(0),
            "a point feature this close to a line landmark is a piece of wall (0: off)");
  v->Double("point_end_margin_m", &o->point_end_margin_m, R::AtLeast(0),
            "...within the landmark's seen extent lengthened by this at both ends");
  v->Double("point_behind_line_m", &o->point_behind_line_m, R::AtLeast(0),
            "a point feature this far behind a line landmark's seen extent is one too (0: off)");
  v->Int("confirm_scans", &o->confirm_scans, R::Between(1, 1000),
         "scans a candidate line is seen in before it becomes a landmark");
  v->Double("candidate_timeout_s", &o->candidate_timeout_s, R::AtLeast(0),
            "a candidate line unseen for longer is dropped");
  v->Double("candidate_match_m", &o->candidate_match_m, R::Above(0),
            "a line feature continues a candidate within this distance...");
  v->Double("candidate_match_rad", &o->candidate_match_rad, R::Above(0),
            "...and this angle", OptionUnit::kDegrees);
  v->Int("max_updates_per_scan", &o->max_updates_per_scan, R::Between(0, 100000),
         "budget of line-landmark updates per scan (0: no limit)");
  v->Int("max_landmarks", &o->max_landmarks, R::Between(0, 100000),
         "the most line landmarks held; new ones beyond are refused and counted");
}

std::vector<uint8_t> PointsOnLineLandmarks(const std::vector<Eigen::Vector2d>& range_bearings,
                                           const LineLandmarkOptions& options,
                                           const SensorMount& mount, const SlamState& state) {
  std::vector<uint8_t> on_line(range_bearings.size(), 0);
  if (!options.enabled ||
      !(options.point_on_line_m > 0.0 || options.point_behind_line_m > 0.0) ||
      state.num_lines() == 0) {
    return on_line;
  }
  const Eigen::Vector3d robot = state.robot_pose();
  const Eigen::Vector2d sensor = SensorPointToMap(robot, mount, Eigen::Vector2d::Zero());
  for (size_t i = 0; i < range_bearings.size(); ++i) {
    const Eigen::Vector2d& z = range_bearings[i];
    const Eigen::Vector2d point =
        SensorPointToMap(robot, mount, z(0) * Eigen::Vector2d(std::cos(z(1)), std::sin(z(1))));
    for (int j = 0; j < state.num_lines() && !on_line[i]; ++j) {
      const Eigen::Vector2d line = state.line_params(j);
      const Eigen::Vector2d normal(std::cos(line(1)), std::sin(line(1)));
      const double across = point.dot(normal) - line(0);
      const LineRecord& record = state.line(j).record;
      if (std::abs(across) <= options.point_on_line_m) {
        const double along = PositionAlongLine(line, point);
        on_line[i] = along >= record.extent_from_m - options.point_end_margin_m &&
                     along <= record.extent_to_m + options.point_end_margin_m;
        continue;
      }
      // Behind: on the other side of the line than the sensor, the beam to it crossing the
      // wall's seen extent (no end margin: past a wall's end the laser does see behind it).
      const double sensor_across = sensor.dot(normal) - line(0);
      if (!(across * sensor_across < 0.0 && std::abs(across) <= options.point_behind_line_m)) {
        continue;
      }
      const Eigen::Vector2d crossing =
          sensor + sensor_across / (sensor_across - across) * (point - sensor);
      const double along = PositionAlongLine(line, crossing);
      on_line[i] = along >= record.extent_from_m && along <= record.extent_to_m;
    }
  }
  return on_line;
}


LineStepCounts UpdateLineLandmarks(const std::vector<LineReading>& lines, int64_t utime,
                                   const LineLandmarkOptions& options, const LineGates& gates,
                                   const SensorMount& mount, int64_t* next_id, SlamState* state,
                                   std::vector<LineCandidate>* candidates) {
  LineStepCounts counts;
  counts.features = static_cast<int>(lines.size());
  DropStaleLineCandidates(utime, options, candidates);
  counts.candidates = static_cast<int>(candidates->size());
  if (!options.enabled || lines.empty()) return counts;
  const std::vector<LineMeasurement> measurements = ValidateLines(lines, options, &counts);
  const LineScan scan{measurements, options, gates, mount, utime};

  // 1. Compatible pairs at the predicted state; 4. the budget they leave.
  const LineGating gating = GateLines(scan, PredictLines(*state, mount), *state);
  LineAssociation association(
      scan.num_features(),
      LinesThatMayUpdate(*state, gating.compatible, options.max_updates_per_scan));
  // 2. Level 1; 3. level 2 at the state level 1 left.
  counts.level1_updates =
      AssociateLinesLevel1(gating.compatible, scan, &association, state, &counts);
  counts.level2_updates =
      AssociateLinesLevel2(gating.compatible, scan, &association, state, &counts);
  // 5. Extents and records of the associated landmarks.
  RecordAssociatedLines(scan, association, state, &counts);
  // 6. New landmarks from the candidates that stay.
  AddConfirmedLines(scan, association, gating.near_landmark, next_id, state, candidates,
                    &counts);
  counts.candidates = static_cast<int>(candidates->size());
  return counts;
}

}  // namespace slammtt
