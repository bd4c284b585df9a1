// Measures the perception figures of issue 11 (Measure) on synthetic offices
// (tests/perception/office_scene.h), 20 seeds from first_seed, 30 scans each, at one beam
// spacing (0.35 degrees: a Hokuyo's; 0.9: the RPLIDAR A2's) within a range: person recall and
// precision (people with at least 3 beams on a leg, 0.3 m match), centre error median and p95,
// the share of point features on walls, line angle and distance errors against the true walls
// and furniture sides (tools/metrics/feature_score.h for the definitions). Pooled figures, and
// per-seed recall and precision (worst seed and median printed).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "perception/segmenter.h"
#include "tests/perception/office_scene.h"
#include "tools/metrics/feature_score.h"

namespace slammtt {
namespace testing_support {


inline Eigen::Vector2d Cartesian(double range_m, double bearing_rad) {
  return range_m * Eigen::Vector2d(std::cos(bearing_rad), std::sin(bearing_rad));
}

struct Figures {
  FeatureScore pooled;
  std::vector<double> seed_recall;
  std::vector<double> seed_precision;
};

inline Figures Measure(double spacing_deg, double max_range_m, uint64_t first_seed) {
  Figures figures;
  FeatureScoreOptions options;
  options.max_range_m = max_range_m;
  Segmenter segmenter(SegmenterOptions{});
  for (uint64_t seed = first_seed; seed < first_seed + 20; ++seed) {
    const auto layout = MakeOfficeLayout(seed);
    std::mt19937_64 rng(1000 + seed);
    FeatureScore seed_score;
    for (int k = 0; k < 30; ++k) {
      const OfficeScan office = MakeOfficeScan(layout, spacing_deg, &rng);
      const std::vector<Feature>& features = segmenter.Segment(office.scan.View());
      std::vector<Eigen::Vector2d> people, points;
      for (const PersonFeature& p : segmenter.people()) {
        people.push_back(Cartesian(p.range_m, p.bearing_rad));
      }
      for (const Feature& f : features) points.push_back(Cartesian(f.range_m, f.bearing_rad));
      std::vector<LineObservation> lines;
      for (const LineFeature& l : segmenter.lines()) {
        lines.push_back({l.rho_m, l.alpha_rad, l.first_point_m, l.last_point_m});
      }
      for (FeatureScore* s : {&seed_score, &figures.pooled}) {
        ScorePeople(people, office.people, options, s);
        ScorePointsOnWalls(points, office.segments, options, s);
        ScoreLines(lines, office.segments, options, s);
      }
    }
    figures.seed_recall.push_back(seed_score.PersonRecall());
    figures.seed_precision.push_back(seed_score.PersonPrecision());
  }
  const FeatureScore& f = figures.pooled;
  std::printf(
      "seeds %llu-%llu, %.2f deg, within %.0f m: people %lld, person features %lld "
      "(ignored %lld): recall %.4f "
      "(worst seed %.4f, median %.4f), precision %.4f (worst %.4f, median %.4f); centre error "
      "median %.4f m, p95 %.4f m; point features %lld, on walls %lld (share %.4f); lines %lld, "
      "matched %lld, angle error median %.3f deg p95 %.3f deg, distance error median %.4f m "
      "p95 %.4f m\n",
      static_cast<unsigned long long>(first_seed), static_cast<unsigned long long>(first_seed + 19),
      spacing_deg, max_range_m, static_cast<long long>(f.people_truth),
      static_cast<long long>(f.person_features), static_cast<long long>(f.person_features_ignored),
      f.PersonRecall(), *std::min_element(figures.seed_recall.begin(), figures.seed_recall.end()),
      Percentile(figures.seed_recall, 0.5), f.PersonPrecision(),
      *std::min_element(figures.seed_precision.begin(), figures.seed_precision.end()),
      Percentile(figures.seed_precision, 0.5), Percentile(f.centre_errors_m, 0.5),
      Percentile(f.centre_errors_m, 0.95), static_cast<long long>(f.point_features),
      static_cast<long long>(f.point_features_on_walls), f.WallPointShare(),
      static_cast<long long>(f.lines), static_cast<long long>(f.lines_matched),
      Percentile(f.line_angle_errors_rad, 0.5) * 180 / M_PI,
      Percentile(f.line_angle_errors_rad, 0.95) * 180 / M_PI,
      Percentile(f.line_distance_errors_m, 0.5), Percentile(f.line_distance_errors_m, 0.95));
  return figures;
}

}  // namespace testing_support
}  // namespace slammtt
