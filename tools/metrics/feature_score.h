// Scores of one scan's perception output (FEATURES: point features, line features, person
// features) against the truth of that moment, all in the sensor frame (x forward, y left).
// Pure: Eigen and the standard library. Definitions (docs/perception.md, "Perception figures"):
//
// - people: the truth set is every person with at least min_leg_beams beams on one of its legs
//   and its centre within max_range_m; person features farther than max_range_m are not
//   scored. Features and truth are matched one-to-one by increasing centre distance within
//   person_match_m (ties: lower feature, then lower person index). An unmatched feature within
//   person_match_m of a person left out of the truth set (fewer beams, or beyond the range) is
//   ignored; any other unmatched feature is a false positive. recall = matched / truth set,
//   precision = matched / (features scored - ignored); centre error = matched distances.
// - points on walls: a point feature lies on a wall when its centre is within wall_distance_m of
//   a wall segment, or behind one (the sight line from the sensor to the centre crosses a wall
//   segment more than wall_distance_m before the centre): a wall piece's fitted centre lands
//   behind the wall. share = on walls / point features.
// - lines: a line feature matches the wall or furniture segment whose infinite line is nearest
//   to both of its observed end points (each within line_match_m) among the segments whose
//   extent overlaps the feature's extent projected on them; angle error = |alpha - alpha_true|
//   wrapped, distance error = |rho - rho_true|. Unmatched lines are counted.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace slammtt {

struct TruthPerson {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  int max_leg_beams = 0;  // beams whose first hit is the person's most visible leg
};

struct TruthSegment {
  Eigen::Vector2d first_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d second_m = Eigen::Vector2d::Zero();
  bool wall = true;  // false: furniture (scored for lines, not for points on walls)
};

struct LineObservation {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
  Eigen::Vector2d first_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_m = Eigen::Vector2d::Zero();
};

struct FeatureScoreOptions {
  double person_match_m = 0.3;
  int min_leg_beams = 3;
  double max_range_m = std::numeric_limits<double>::infinity();
  double wall_distance_m = 0.1;
  double line_match_m = 0.2;
};

// Sums over scans (ScorePeople / ScorePointsOnWalls / ScoreLines add to it).
struct FeatureScore {
  int64_t people_truth = 0;
  int64_t people_matched = 0;
  int64_t person_features = 0;          // scored (within max_range_m)
  int64_t person_features_ignored = 0;  // near a person outside the truth set
  std::vector<double> centre_errors_m;
  int64_t point_features = 0;
  int64_t point_features_on_walls = 0;
  int64_t lines = 0;
  int64_t lines_matched = 0;
  std::vector<double> line_angle_errors_rad;
  std::vector<double> line_distance_errors_m;

  double PersonRecall() const;     // NaN without truth
  double PersonPrecision() const;  // NaN without scored features
  double WallPointShare() const;   // NaN without point features
};

// What became of each person feature in ScorePeople.
enum PersonFeatureOutcome : int {
  kPersonNotScored = -3,  // not finite, or beyond max_range_m
  kPersonFalse = -2,      // a false positive
  kPersonIgnored = -1,    // near a person outside the truth set
  // >= 0: matched to people[outcome]
};

// Non-finite inputs are skipped (a NaN feature is neither matched nor counted). With `outcome`,
// it receives one PersonFeatureOutcome (or the matched person's index) per feature.
void ScorePeople(const std::vector<Eigen::Vector2d>& person_features,
                 const std::vector<TruthPerson>& people, const FeatureScoreOptions& options,
                 FeatureScore* score, std::vector<int>* outcome = nullptr);
void ScorePointsOnWalls(const std::vector<Eigen::Vector2d>& point_features,
                        const std::vector<TruthSegment>& segments,
                        const FeatureScoreOptions& options, FeatureScore* score);
void ScoreLines(const std::vector<LineObservation>& lines,
                const std::vector<TruthSegment>& segments, const FeatureScoreOptions& options,
                FeatureScore* score);

}  // namespace slammtt
