#include "tools/metrics/feature_score.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "common/angle.h"

namespace slammtt {
namespace {

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance from the origin along the sight line to `target` at which it crosses segment a-b,
// or infinity.
double SightLineCrossing(const Eigen::Vector2d& target, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double denominator = target.x() * e.y() - target.y() * e.x();
  if (std::abs(denominator) < 1e-12) return std::numeric_limits<double>::infinity();
  const double t = (a.x() * e.y() - a.y() * e.x()) / denominator;  // fraction of the sight line
  const double s = (a.x() * target.y() - a.y() * target.x()) / denominator;
  if (t <= 0.0 || t >= 1.0 || s < 0.0 || s > 1.0) return std::numeric_limits<double>::infinity();
  return t * target.norm();
}

// Hessian normal form of the line through a and b, normal from the origin towards it.
void SegmentLine(const TruthSegment& s, double* rho, double* alpha) {
  const Eigen::Vector2d e = s.second_m - s.first_m;
  double a = std::atan2(e.x(), -e.y());
  double r = s.first_m.x() * std::cos(a) + s.first_m.y() * std::sin(a);
  if (r < 0.0) {
    r = -r;
    a += M_PI;
  }
  *rho = r;
  *alpha = WrapAngle(a);
}

}  // namespace

double FeatureScore::PersonRecall() const {
  return people_truth > 0 ? double(people_matched) / double(people_truth) : std::nan("");
}

double FeatureScore::PersonPrecision() const {
  const int64_t counted = person_features - person_features_ignored;
  return counted > 0 ? double(people_matched) / double(counted) : std::nan("");
}

double FeatureScore::WallPointShare() const {
  return point_features > 0 ? double(point_features_on_walls) / double(point_features)
                            : std::nan("");
}

void ScorePeople(const std::vector<Eigen::Vector2d>& person_features,
                 const std::vector<TruthPerson>& people, const FeatureScoreOptions& options,
                 FeatureScore* score, std::vector<int>* outcome) {
  if (outcome != nullptr) outcome->assign(person_features.size(), kPersonNotScored);
  std::vector<size_t> features;
  for (size_t i = 0; i < person_features.size(); ++i) {
    const Eigen::Vector2d& f = person_features[i];
    if (f.allFinite() && f.norm() <= options.max_range_m) features.push_back(i);
  }
  std::vector<size_t> truth;
  std::vector<size_t> others;  // outside the truth set
  for (size_t j = 0; j < people.size(); ++j) {
    if (!people[j].centre_m.allFinite()) continue;
    const bool in_set = people[j].max_leg_beams >= options.min_leg_beams &&
                        people[j].centre_m.norm() <= options.max_range_m;
    (in_set ? truth : others).push_back(j);
  }
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t fi = 0; fi < features.size(); ++fi) {
    for (size_t tj = 0; tj < truth.size(); ++tj) {
      const double d = (person_features[features[fi]] - people[truth[tj]].centre_m).norm();
      if (d <= options.person_match_m) pairs.emplace_back(d, fi, tj);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> feature_used(features.size(), false);
  std::vector<bool> truth_used(truth.size(), false);
  for (const auto& [d, fi, tj] : pairs) {
    if (feature_used[fi] || truth_used[tj]) continue;
    feature_used[fi] = true;
    truth_used[tj] = true;
    ++score->people_matched;
    score->centre_errors_m.push_back(d);
    if (outcome != nullptr) (*outcome)[features[fi]] = static_cast<int>(truth[tj]);
  }
  for (size_t fi = 0; fi < features.size(); ++fi) {
    if (feature_used[fi]) continue;
    int result = kPersonFalse;
    for (size_t j : others) {
      if ((person_features[features[fi]] - people[j].centre_m).norm() <= options.person_match_m) {
        ++score->person_features_ignored;
        result = kPersonIgnored;
        break;
      }
    }
    if (outcome != nullptr) (*outcome)[features[fi]] = result;
  }
  score->people_truth += static_cast<int64_t>(truth.size());
  score->person_features += static_cast<int64_t>(features.size());
}

void ScorePointsOnWalls(const std::vector<Eigen::Vector2d>& point_features,
                        const std::vector<TruthSegment>& segments,
                        const FeatureScoreOptions& options, FeatureScore* score) {
  for (const Eigen::Vector2d& p : point_features) {
    if (!p.allFinite()) continue;
    ++score->point_features;
    const double range = p.norm();
    for (const TruthSegment& s : segments) {
      if (!s.wall) continue;
      if (DistanceToSegment(p, s.first_m, s.second_m) <= options.wall_distance_m ||
          SightLineCrossing(p, s.first_m, s.second_m) < range - options.wall_distance_m) {
        ++score->point_features_on_walls;
        break;
      }
    }
  }
}

void ScoreLines(const std::vector<LineObservation>& lines,
                const std::vector<TruthSegment>& segments, const FeatureScoreOptions& options,
                FeatureScore* score) {
  for (const LineObservation& line : lines) {
    if (!std::isfinite(line.rho_m) || !std::isfinite(line.alpha_rad) ||
        !line.first_m.allFinite() || !line.last_m.allFinite()) {
      continue;
    }
    ++score->lines;
    double best = std::numeric_limits<double>::infinity();
    double best_rho = 0.0;
    double best_alpha = 0.0;
    for (const TruthSegment& s : segments) {
      const Eigen::Vector2d e = s.second_m - s.first_m;
      const double length2 = e.squaredNorm();
      if (!(length2 > 0.0)) continue;
      double rho = 0.0;
      double alpha = 0.0;
      SegmentLine(s, &rho, &alpha);
      const Eigen::Vector2d n(std::cos(alpha), std::sin(alpha));
      const double d0 = std::abs(line.first_m.dot(n) - rho);
      const double d1 = std::abs(line.last_m.dot(n) - rho);
      if (d0 > options.line_match_m || d1 > options.line_match_m) continue;
      // The extents overlap along the segment.
      const double t0 = (line.first_m - s.first_m).dot(e) / length2;
      const double t1 = (line.last_m - s.first_m).dot(e) / length2;
      if (std::max(t0, t1) < 0.0 || std::min(t0, t1) > 1.0) continue;
      if (d0 + d1 < best) {
        best = d0 + d1;
        best_rho = rho;
        best_alpha = alpha;
      }
    }
    if (!std::isfinite(best)) continue;
    ++score->lines_matched;
    score->line_angle_errors_rad.push_back(std::abs(WrapAngle(line.alpha_rad - best_alpha)));
    score->line_distance_errors_m.push_back(std::abs(line.rho_m - best_rho));
  }
}

}  // namespace slammtt
