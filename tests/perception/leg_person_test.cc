// Leg-likeness of compact clusters and person features from legs, on their own and inside the
// segmenter, at 0.35 and 0.9 degree beam spacing.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "perception/leg_likeness.h"
#include "perception/person_detection.h"
#include "perception/segmenter.h"
#include "tests/perception/synthetic_scan.h"

namespace slammtt {
namespace {

using testing_support::CastScene;
using testing_support::Circle;
using testing_support::EvenAngles;
using testing_support::TestScan;
using testing_support::WallSegment;

constexpr double kDeg = M_PI / 180.0;

std::vector<double> Angles(double spacing_deg) {
  return EvenAngles(-M_PI, 2.0 * M_PI, static_cast<int>(std::lround(360.0 / spacing_deg)), true);
}

// The leg-likeness of the one point feature of a scene (or -1 when there is none).
// The shape score (LegClassifier::kShape) unless told otherwise.
double LikenessOf(const std::vector<Circle>& circles, const std::vector<WallSegment>& walls,
                  double spacing_deg, uint64_t seed, double sigma_m = 0.01,
                  double configured_sigma_r_m = 0.03,
                  LegClassifier classifier = LegClassifier::kShape) {
  std::mt19937_64 rng(seed);
  const TestScan scan = CastScene(circles, walls, Angles(spacing_deg), 12.0, sigma_m, 0.0, &rng);
  SegmenterOptions options;
  options.leg_classifier = classifier;
  options.sigma_r_m = configured_sigma_r_m;
  options.min_points = 1;  // see every cluster
  Segmenter segmenter(options);
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  return features.size() == 1 ? features[0].leg_likeness : -1.0;
}

TEST(LegLikenessTest, LegsScoreHighAndOtherThingsLow) {
  const std::vector<WallSegment> back = {{6.0, -5.0, 6.0, 5.0}};
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(seed);
    // A leg (radius 6 cm) at 2 m, both resolutions.
    EXPECT_GT(LikenessOf({{2.0, 0.3, 0.06}}, back, 0.35, seed), 0.6);
    EXPECT_GT(LikenessOf({{2.0, 0.3, 0.06}}, back, 0.9, seed), 0.5);
    // A chair leg (radius 1.5 cm) at 2 m, 0.35 degrees: too thin.
    EXPECT_LT(LikenessOf({{2.0, 0.3, 0.015}}, back, 0.35, seed), 0.2);
    // A disc person of the paper's scenarios (radius 0.25 m): too wide.
    EXPECT_LT(LikenessOf({{2.5, 0.3, 0.25}}, back, 0.35, seed), 0.1);
  }
}

// A 0.15 m board face on at 1.5 m, 0.35 degrees, 5 mm noise: always below a leg of the same
// width there; below the threshold when sigma_r_m says how noisy the sensor is (with the
// paper's 0.03 m the flatness of 0.15 m is not significant).
TEST(LegLikenessTest, FlatBoardScoresBelowALeg) {
  constexpr double kShapeThreshold = 0.65;  // where the shape score was measured
  const std::vector<WallSegment> board = {{1.5, -0.075, 1.5, 0.075}, {6.0, -5.0, 6.0, 5.0}};
  const std::vector<WallSegment> back = {{6.0, -5.0, 6.0, 5.0}};
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    EXPECT_LT(LikenessOf({}, board, 0.35, seed, 0.005),
              LikenessOf({{1.575, 0.0, 0.075}}, back, 0.35, seed, 0.005)) << seed;
    EXPECT_LT(LikenessOf({}, board, 0.35, seed, 0.005, 0.005), kShapeThreshold) << seed;
  }
}

TEST(LegLikenessTest, ShapeCuesFollowTheBeamSpacing) {
  // The same width seen with coarse beams leaves a wider interval for the diameter.
  const double bearings[3] = {-0.03, 0.0, 0.03};
  const double ranges[3] = {2.0, 1.98, 2.0};
  double x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = ranges[i] * std::cos(bearings[i]);
    y[i] = ranges[i] * std::sin(bearings[i]);
  }
  ClusterView view;
  view.bearing_rad = bearings;
  view.range_m = ranges;
  view.x_m = x;
  view.y_m = y;
  view.count = 3;
  const ClusterShape shape = DescribeClusterShape(view, 0.0);
  EXPECT_NEAR(shape.spacing_rad, 0.03, 1e-12);
  EXPECT_NEAR(shape.diameter_high_m - shape.diameter_low_m, 2.0 * 1.9933 * 0.03, 1e-3);
  EXPECT_GT(shape.bulge_m, 0.015);
  const LegLikenessOptions options;
  EXPECT_GT(LegLikeness(shape, options, 0.01), 0.5);
  ClusterShape bad = shape;
  bad.bulge_m = std::nan("");
  EXPECT_EQ(LegLikeness(bad, options, 0.01), 0.0);
  bad = shape;
  bad.num_points = 0;
  EXPECT_EQ(LegLikeness(bad, options, 0.01), 0.0);
  // An edge hidden by a nearer object lowers the score.
  ClusterShape hidden = shape;
  hidden.first_edge_occluded = true;
  hidden.last_edge_occluded = true;
  EXPECT_LT(LegLikeness(hidden, options, 0.01), LegLikeness(shape, options, 0.01));
}

LegCandidate Leg(double x, double y, double likeness, int32_t index, bool provisional = false) {
  LegCandidate c;
  c.range_m = std::hypot(x, y);
  c.bearing_rad = std::atan2(y, x);
  c.covariance << 0.0004, 0.0, 0.0, 1e-4;
  c.leg_likeness = likeness;
  c.feature_index = index;
  c.provisional = provisional;
  return c;
}

// A detector and the buffers of its output; each test sets the options it measures.
class PersonDetectorTest : public ::testing::Test {
 protected:
  PersonDetector detector;
  PersonDetectionOptions options;
  std::vector<PersonFeature> people;
  std::vector<uint8_t> used;
};

TEST_F(PersonDetectorTest, PairsCloseLegsAndKeepsSingleLegs) {
  // Person A: legs 0.25 m apart at 2 m; a lone leg 2 m to the left.
  detector.Detect({Leg(2.0, 0.125, 0.9, 0), Leg(2.0, -0.125, 0.8, 1), Leg(0.0, 2.0, 0.9, 2)},
                  options, &people, &used);
  ASSERT_EQ(people.size(), 2u);
  const PersonFeature& pair = people[0].num_legs == 2 ? people[0] : people[1];
  const PersonFeature& single = people[0].num_legs == 2 ? people[1] : people[0];
  EXPECT_NEAR(pair.range_m, 2.0, 1e-9);
  EXPECT_NEAR(pair.bearing_rad, 0.0, 1e-9);
  EXPECT_EQ(pair.leg_index[0], 0);
  EXPECT_EQ(pair.leg_index[1], 1);
  EXPECT_NEAR(pair.confidence, std::sqrt(0.9 * 0.8), 1e-12);
  EXPECT_EQ(single.num_legs, 1);
  EXPECT_EQ(single.leg_index[0], 2);
  EXPECT_EQ(single.leg_index[1], -1);
  // The single leg's centre is less certain than the pair's (in metres at the person).
  const double pair_lateral = pair.range_m * std::sqrt(pair.covariance(1, 1));
  const double single_lateral = single.range_m * std::sqrt(single.covariance(1, 1));
  EXPECT_GT(single_lateral, 2.0 * pair_lateral);
  EXPECT_GT(single.covariance(0, 0), 2.0 * pair.covariance(0, 0));
  for (const PersonFeature& p : people) EXPECT_GT(p.covariance.determinant(), 0.0);
  EXPECT_EQ(used, (std::vector<uint8_t>{1, 1, 1}));
}

// A scan for SightLines: beams every 0.35 degrees all round, 10 m away except where `ranges`
// puts something nearer (bearing interval in degrees -> range).
struct SightScan {
  std::vector<double> angle_rad, range_m;
  SightLines View() const {
    SightLines sight;
    sight.angle_rad = angle_rad.data();
    sight.range_m = range_m.data();
    sight.count = angle_rad.size();
    sight.max_gap_rad = 5.0 * kDeg;
    return sight;
  }
};
SightScan MakeSightScan(const std::vector<std::array<double, 3>>& nearer) {
  SightScan scan;
  for (int i = 0; i < 1024; ++i) {
    const double a = -M_PI + (i + 0.5) * 2.0 * M_PI / 1024;
    double r = 10.0;
    for (const auto& [from_deg, to_deg, range] : nearer) {
      if (a >= from_deg * kDeg && a <= to_deg * kDeg) r = std::min(r, range);
    }
    scan.angle_rad.push_back(a);
    scan.range_m.push_back(r);
  }
  return scan;
}

TEST_F(PersonDetectorTest, OneLegCentreLiesWhereTheOtherLegCanHide) {
  options.hidden_leg_centre = true;
  // A lone leg (radius 0.06 m) at 2 m, bearing 0: its shadow is the only place the scan does
  // not see, so the other leg is behind it and the body beyond the leg along the sight line.
  const double half_deg = std::atan(0.06 / 2.0) / kDeg;
  const SightScan open = MakeSightScan({{-half_deg, half_deg, 1.94}});
  const SightLines open_view = open.View();
  detector.Detect({Leg(2.0, 0.0, 0.9, 0)}, options, &people, &used, &open_view);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 1);
  EXPECT_GT(people[0].range_m, 2.1);
  EXPECT_LT(people[0].range_m, 2.0 + 0.5 * options.max_leg_separation_m);
  EXPECT_NEAR(people[0].bearing_rad, 0.0, 0.01);
  // A box to the left (bearings 4-14 degrees, 1.5 m) hides places near the leg too: the body
  // moves towards it.
  const SightScan boxed = MakeSightScan({{-half_deg, half_deg, 1.94}, {4.0, 14.0, 1.5}});
  const SightLines boxed_view = boxed.View();
  detector.Detect({Leg(2.0, 0.0, 0.9, 0)}, options, &people, &used, &boxed_view);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_GT(people[0].bearing_rad, 0.02);
  // A scan that sees every place around the leg (not even the leg's own shadow: a contrived
  // scan) leaves the centre on the leg.
  const SightScan none = MakeSightScan({});
  const SightLines none_view = none.View();
  detector.Detect({Leg(2.0, 0.0, 0.9, 0)}, options, &people, &used, &none_view);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].range_m, 2.0, 1e-9);
  EXPECT_NEAR(people[0].bearing_rad, 0.0, 1e-9);
  // Switched off, or without a scan: on the leg.
  options.hidden_leg_centre = false;
  detector.Detect({Leg(2.0, 0.0, 0.9, 0)}, options, &people, &used, &open_view);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].range_m, 2.0, 1e-9);
  options.hidden_leg_centre = true;
  detector.Detect({Leg(2.0, 0.0, 0.9, 0)}, options, &people, &used, nullptr);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].range_m, 2.0, 1e-9);
  // Pairs are not moved.
  detector.Detect({Leg(2.0, 0.125, 0.9, 0), Leg(2.0, -0.125, 0.8, 1)}, options, &people, &used,
                  &open_view);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].range_m, 2.0, 1e-9);
}

TEST_F(PersonDetectorTest, SeparationBoundsAndGreedyPairing) {
  // Two legs 0.8 m apart: two single-leg people, not one.
  detector.Detect({Leg(2.0, 0.4, 0.9, 0), Leg(2.0, -0.4, 0.9, 1)}, options, &people, &used);
  ASSERT_EQ(people.size(), 2u);
  EXPECT_EQ(people[0].num_legs + people[1].num_legs, 2);
  // Three legs in a row 0.2 and 0.3 m apart: the closest pair is the person.
  detector.Detect({Leg(2.0, 0.0, 0.9, 0), Leg(2.0, 0.2, 0.9, 1), Leg(2.0, 0.5, 0.6, 2)}, options,
                  &people, &used);
  int pairs = 0;
  for (const PersonFeature& p : people) {
    if (p.num_legs != 2) continue;
    ++pairs;
    EXPECT_EQ(p.leg_index[0], 0);
    EXPECT_EQ(p.leg_index[1], 1);
  }
  EXPECT_EQ(pairs, 1);
  // The third leg (0.6) is below single_leg_threshold (0.7): no person of its own.
  EXPECT_EQ(people.size(), 1u);
  EXPECT_EQ(used[2], 0);
}

TEST_F(PersonDetectorTest, ProvisionalLegsOnlyJoinARealLeg) {
  detector.Detect({Leg(4.0, 0.1, 0.9, -2, true), Leg(4.0, -0.1, 0.9, -3, true)}, options, &people,
                  &used);
  EXPECT_TRUE(people.empty());
  detector.Detect({Leg(4.0, 0.1, 0.9, 0), Leg(4.0, -0.1, 0.9, -2, true)}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 2);
}

TEST_F(PersonDetectorTest, SurfacePiecesMakeNoPersonAloneAndNoPairTogether) {
  LegCandidate piece = Leg(3.0, 0.0, 0.95, 0);
  piece.surface_piece = true;
  LegCandidate other_piece = Leg(3.0, 0.3, 0.95, 1);
  other_piece.surface_piece = true;
  // Alone, or with another piece 0.3 m away: no person.
  detector.Detect({piece}, options, &people, &used);
  EXPECT_TRUE(people.empty());
  detector.Detect({piece, other_piece}, options, &people, &used);
  EXPECT_TRUE(people.empty());
  EXPECT_EQ(used, (std::vector<uint8_t>{0, 0}));
  // Beside a leg that is not a piece, it may still be the other leg.
  detector.Detect({piece, Leg(3.0, 0.3, 0.95, 1)}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 2);
}

TEST_F(PersonDetectorTest, ALegRightInFrontOfASurfaceMakesNoPersonAlone) {
  options.single_leg_surface_clearance_m = 0.2;
  LegCandidate against = Leg(3.0, 0.0, 0.95, 0);
  against.surface_clearance_m = 0.12;  // no room behind it for the other leg
  LegCandidate clear = Leg(0.0, 3.0, 0.95, 1);
  clear.surface_clearance_m = 0.25;
  detector.Detect({against, clear}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].leg_index[0], 1);
  EXPECT_EQ(used, (std::vector<uint8_t>{0, 1}));
  // Two legs in front of a wall are a person.
  LegCandidate beside = Leg(3.0, 0.3, 0.95, 1);
  beside.surface_clearance_m = 0.12;
  detector.Detect({against, beside}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 2);
  // Without the rule the leg alone is a person.
  options.single_leg_surface_clearance_m = 0.0;
  detector.Detect({against}, options, &people, &used);
  EXPECT_EQ(people.size(), 1u);
}

TEST_F(PersonDetectorTest, PiecesOfOneDropoutRunMakeNoPerson) {
  options.separate_dropout_pieces = true;
  LegCandidate a = Leg(3.0, 0.0, 0.95, 0);
  LegCandidate b = Leg(3.0, 0.3, 0.95, 1);
  LegCandidate c = Leg(3.0, 0.6, 0.95, 2);
  a.dropout_run = b.dropout_run = c.dropout_run = 0;
  detector.Detect({a, b, c}, options, &people, &used);
  EXPECT_TRUE(people.empty());
  EXPECT_EQ(used, (std::vector<uint8_t>{0, 0, 0}));
  // A leg of another run or of none may still pair with one of them.
  LegCandidate leg = Leg(3.0, -0.3, 0.95, 3);
  detector.Detect({a, b, c, leg}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 2);
  // Without the rule: pairs and a one-leg person.
  options.separate_dropout_pieces = false;
  detector.Detect({a, b, c}, options, &people, &used);
  EXPECT_EQ(people.size(), 2u);
}

TEST_F(PersonDetectorTest, AShortLegWithAnOpenEdgeIsAStub) {
  options.single_leg_open_edge_max_points = 3;
  LegCandidate stub = Leg(3.0, 0.0, 0.95, 0);
  stub.num_points = 3;
  stub.open_edges = 1;
  LegCandidate longer = Leg(0.0, 3.0, 0.95, 1);  // four points: enough of a shape
  longer.num_points = 4;
  longer.open_edges = 1;
  LegCandidate bounded = Leg(-3.0, 0.0, 0.95, 2);  // three points, a return on both sides
  bounded.num_points = 3;
  detector.Detect({stub, longer, bounded}, options, &people, &used);
  ASSERT_EQ(people.size(), 2u);
  for (const PersonFeature& p : people) EXPECT_NE(p.leg_index[0], 0);
  EXPECT_EQ(used, (std::vector<uint8_t>{kStubLeg, 1, 1}));
  // A stub may still be the other leg of a person.
  detector.Detect({stub, Leg(3.0, 0.3, 0.95, 1)}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].num_legs, 2);
  EXPECT_EQ(used, (std::vector<uint8_t>{1, 1}));
  // Without the rule (the default) it is a one-leg person.
  options.single_leg_open_edge_max_points = PersonDetectionOptions{}.single_leg_open_edge_max_points;
  ASSERT_EQ(options.single_leg_open_edge_max_points, 0);
  detector.Detect({stub}, options, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(used, (std::vector<uint8_t>{1}));
}

TEST_F(PersonDetectorTest, NonFiniteCandidatesAreSkipped) {
  LegCandidate nan_leg = Leg(2.0, 0.1, 0.9, 0);
  nan_leg.range_m = std::nan("");
  detector.Detect({nan_leg, Leg(2.0, -0.1, 0.9, 1)}, PersonDetectionOptions{}, &people, &used);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_EQ(people[0].leg_index[0], 1);
  EXPECT_TRUE(people[0].covariance.allFinite());
}

TEST_F(PersonDetectorTest, CovarianceConversionsRoundTrip) {
  Eigen::Matrix2d polar;
  polar << 0.01, 0.001, 0.001, 0.0004;
  const double r = 3.0, b = 0.7;
  const Eigen::Matrix2d cartesian = PolarToCartesianCovariance(r, b, polar);
  const Eigen::Matrix2d back = CartesianToPolarCovariance(r * std::cos(b), r * std::sin(b),
                                                          cartesian);
  EXPECT_LT((back - polar).norm(), 1e-12);
}

// A person on two legs in front of a wall, walking across the view: a person feature within a
// few centimetres of the midpoint of the legs, at 0.35 and at 0.9 degrees.
TEST(SegmenterPeopleTest, TwoLegsGiveOnePersonAtBothResolutions) {
  for (double spacing : {0.35, 0.9}) {
    int two_legs = 0;
    for (uint64_t seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE(testing::Message() << spacing << " deg, seed " << seed);
      std::mt19937_64 rng(seed);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const double cx = 2.0 + 0.3 * u(rng), cy = 0.5 * u(rng);
      // Legs apart along the walking direction (y) by up to 0.5 m (within max_leg_separation_m
      // with the 0.2 m across)...
      const double stride = 0.25 * u(rng);
      const std::vector<Circle> legs = {{cx + 0.1, cy + stride, 0.06},  // ...and 0.2 m across
                                        {cx - 0.1, cy - stride, 0.06}};
      const TestScan scan = CastScene(legs, {{5.0, -4.0, 5.0, 4.0}}, Angles(spacing), 12.0, 0.01,
                                      0.0, &rng);
      Segmenter segmenter(SegmenterOptions{});
      const std::vector<Feature>& features = segmenter.Segment(scan.View());
      ASSERT_LE(segmenter.people().size(), 1u);
      if (segmenter.people().empty()) continue;  // counted below
      const PersonFeature& p = segmenter.people()[0];
      // One leg may hide the other, or both be one cluster: then the person has one "leg".
      if (p.num_legs != 2) continue;
      ++two_legs;
      const double px = p.range_m * std::cos(p.bearing_rad);
      const double py = p.range_m * std::sin(p.bearing_rad);
      EXPECT_LT(std::hypot(px - cx, py - cy), 0.06);
      for (int32_t leg : p.leg_index) {
        ASSERT_GE(leg, 0);
        ASSERT_LT(leg, static_cast<int32_t>(features.size()));
        EXPECT_GE(features[static_cast<size_t>(leg)].leg_likeness, 0.5);
      }
    }
    std::printf("%.2f deg: %d of 20 scenes give a two-leg person\n", spacing, two_legs);
    EXPECT_GE(two_legs, spacing < 0.5 ? 16 : 15) << spacing;  // measured 18 and 17
  }
}

// At 0.9 degrees and 3.5 m a leg is two or three beams: a two-beam leg joins its partner as a
// provisional leg and becomes a point feature; at 0.35 degrees nothing is provisional.
TEST(SegmenterPeopleTest, FarLegsOfTwoBeamsJoinTheirPartner) {
  int two_leg_people = 0;
  int provisional_used = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double cx = 3.2, cy = 0.3 * u(rng);
    const std::vector<Circle> legs = {{cx, cy + 0.15, 0.05}, {cx, cy - 0.15, 0.07}};
    const TestScan scan =
        CastScene(legs, {{7.0, -6.0, 7.0, 6.0}}, Angles(0.9), 12.0, 0.01, 0.0, &rng);
    Segmenter segmenter(SegmenterOptions{});
    const std::vector<Feature>& features = segmenter.Segment(scan.View());
    for (const PersonFeature& p : segmenter.people()) {
      if (p.num_legs != 2) continue;
      ++two_leg_people;
      for (int32_t leg : p.leg_index) ASSERT_LT(leg, static_cast<int32_t>(features.size()));
    }
    provisional_used += static_cast<int>(segmenter.stats().provisional_legs_used);
    for (size_t i = 1; i < features.size(); ++i) {
      EXPECT_LE(features[i - 1].bearing_rad, features[i].bearing_rad);
    }
  }
  EXPECT_GE(two_leg_people, 10);
  EXPECT_GT(provisional_used, 5);
}

// The end of a wall beside an opening, as the world's office shows it down its corridor: a flat
// piece 0.15 m wide with nothing returning on either side (the opening; the corridor wall at
// grazing incidence, which gives no return). Its edges are unbounded and it makes no person,
// except where the range noise makes it look convex (convexity 0.1 or more: measured in 1 of 10
// scenes at 0.35 degrees, 2 of 10 at 0.9); the same piece in front of a far wall has both edges
// bounded.
// A leg-sized round object seen by three beams at the RPLIDAR's 0.9 degrees in front of a far
// wall, built beam by beam. With person_single_leg_open_edge_max_points 3, where the beam
// beside it gives no return (a dropout at grazing incidence, or nothing in range) it is a stub:
// no person and no point feature, counted in leg_stubs. With a return on both sides, or seen
// by four beams, it stays a one-leg person, and without the rule (the default) the stub is one.
// Every cluster is a leg candidate and a one-leg person here (thresholds 0), so only the rule
// decides.
TEST(SegmenterPeopleTest, AThreeBeamLegBesideANoReturnIsAStub) {
  const double step = 0.9 * M_PI / 180.0;
  // Beams from -30 to +30 degrees; a wall at x = 6 m; a circle of `radius` at `range` whose
  // centre is at bearing `centre_rad`; `open` makes the beam just after the object invalid.
  const auto scan_of = [&](double range, double radius, double centre_rad, bool open) {
    TestScan scan;
    const Eigen::Vector2d centre = range * Eigen::Vector2d(std::cos(centre_rad), std::sin(centre_rad));
    int last_hit = -1;
    for (int i = -33; i <= 33; ++i) {
      const double a = i * step;
      const Eigen::Vector2d u(std::cos(a), std::sin(a));
      double r = 6.0 / u.x();
      const double along = centre.dot(u);
      const double miss2 = centre.squaredNorm() - along * along;
      if (miss2 < radius * radius) {
        r = along - std::sqrt(radius * radius - miss2);
        last_hit = static_cast<int>(scan.angle_rad.size());
      }
      scan.angle_rad.push_back(static_cast<float>(a));
      scan.range_m.push_back(static_cast<float>(r));
      scan.valid.push_back(1);
    }
    if (open) scan.valid[static_cast<size_t>(last_hit + 1)] = 0;
    return scan;
  };
  SegmenterOptions options;
  options.leg_threshold = 0.0;
  options.person.single_leg_threshold = 0.0;
  options.person.single_leg_open_edge_max_points = 3;
  const auto near_object = [](const std::vector<Feature>& features, double range) {
    int count = 0;
    for (const Feature& f : features) count += std::abs(f.range_m - range) < 0.2;
    return count;
  };
  const auto people_near = [](const Segmenter& segmenter, double range) {
    int count = 0;
    for (const PersonFeature& p : segmenter.people()) count += std::abs(p.range_m - range) < 0.2;
    return count;
  };
  {  // three beams, open edge: a stub
    const TestScan scan = scan_of(3.0, 0.06, 0.0, true);
    Segmenter segmenter(options);
    const std::vector<Feature>& features = segmenter.Segment(scan.View());
    EXPECT_EQ(near_object(features, 3.0), 0);
    EXPECT_EQ(people_near(segmenter, 3.0), 0);
    EXPECT_EQ(segmenter.stats().leg_stubs, 1);
    // Every person's legs are still point features of the scan.
    for (const PersonFeature& p : segmenter.people()) {
      for (int k = 0; k < p.num_legs; ++k) {
        ASSERT_GE(p.leg_index[k], 0);
        ASSERT_LT(static_cast<size_t>(p.leg_index[k]), features.size());
      }
    }
  }
  // A scan whose object (`points` beams) stays one point feature and one one-leg person.
  const auto expect_one_leg_person = [&](const TestScan& scan, int points) {
    Segmenter segmenter(options);
    const std::vector<Feature>& features = segmenter.Segment(scan.View());
    ASSERT_EQ(near_object(features, 3.0), 1);
    for (const Feature& f : features) {
      if (std::abs(f.range_m - 3.0) < 0.2) {
        EXPECT_EQ(f.num_points, points);
      }
    }
    EXPECT_EQ(people_near(segmenter, 3.0), 1);
    EXPECT_EQ(segmenter.stats().leg_stubs, 0);
  };
  {
    SCOPED_TRACE("three beams, a return on both sides: a one-leg person");
    expect_one_leg_person(scan_of(3.0, 0.06, 0.0, false), 3);
  }
  {
    SCOPED_TRACE("four beams, open edge: a one-leg person");
    expect_one_leg_person(scan_of(3.0, 0.075, 0.5 * step, true), 4);
  }
  {
    SCOPED_TRACE("without the rule (the default) the stub is a one-leg person");
    options.person.single_leg_open_edge_max_points =
        SegmenterOptions{}.person.single_leg_open_edge_max_points;
    expect_one_leg_person(scan_of(3.0, 0.06, 0.0, true), 3);
  }
}

TEST(SegmenterPeopleTest, AFlatPieceBetweenNoReturnsIsNoPerson) {
  for (double spacing : {0.35, 0.9}) {
    int scenes_with_people = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      SCOPED_TRACE(testing::Message() << spacing << " deg, seed " << seed);
      std::mt19937_64 rng(seed);
      const WallSegment stub = {2.5, -0.075, 2.5, 0.075};
      for (bool background : {false, true}) {
        std::vector<WallSegment> walls = {stub};
        if (background) walls.push_back({6.0, -5.0, 6.0, 5.0});
        const TestScan scan = CastScene({}, walls, Angles(spacing), 12.0, 0.01, 0.0, &rng);
        Segmenter segmenter(SegmenterOptions{});
        const std::vector<Feature>& features = segmenter.Segment(scan.View());
        const Feature* piece = nullptr;
        for (const Feature& f : features) {
          if (std::abs(f.bearing_rad) < 0.05 && f.range_m < 3.0) piece = &f;
        }
        ASSERT_NE(piece, nullptr);
        EXPECT_EQ(piece->bounded_edges, background ? 2 : 0);
        if (!background) scenes_with_people += !segmenter.people().empty();
      }
    }
    EXPECT_LE(scenes_with_people, 2) << spacing;
  }
}

// A stub of a wall beyond an opening, in line with the wall the sensor faces (the world's door
// frames and corridor ends): every point within the range noise of the wall's line feature, so
// it is a piece of that line even where it looks like a leg (leg_threshold 0 makes every
// cluster leg-like: only the tight on-line test, kOnSurfaceM, can then reject it). A leg
// standing on the same line, centred on it, is round: its outline departs from the line by up
// to its radius and it stays a point feature; so does a leg 0.1 m in front of the line.
TEST(SegmenterPeopleTest, AStubInLineWithAWallIsAPieceOfItAndALegThereIsNot) {
  SegmenterOptions options;
  options.leg_threshold = 0.0;
  const WallSegment wall = {3.0, 0.3, 3.0, 3.0};
  int stubs_on_line = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937_64 rng(seed);
    const auto fate_near = [&](const std::vector<Circle>& circles,
                               const std::vector<WallSegment>& walls, double x_m, double y_m) {
      const TestScan scan = CastScene(circles, walls, Angles(0.35), 12.0, 0.01, 0.0, &rng);
      Segmenter segmenter(options);
      segmenter.Segment(scan.View());
      EXPECT_FALSE(segmenter.lines().empty());
      for (const LegClusterRecord& r : segmenter.leg_clusters()) {
        if (std::hypot(r.centroid_x_m - x_m, r.centroid_y_m - y_m) < 0.1) return r.fate;
      }
      ADD_FAILURE() << "no cluster near y = " << y_m;
      return LegClusterFate::kNotALeg;
    };
    stubs_on_line +=
        fate_near({}, {wall, {3.0, -0.2, 3.0, -0.1}}, 3.0, -0.15) == LegClusterFate::kOnALine;
    // Centroids: the legs' visible arcs, about half a radius in front of their centres.
    EXPECT_EQ(fate_near({{3.0, -0.15, 0.06}}, {wall}, 2.96, -0.15),
              LegClusterFate::kPointFeature);
    EXPECT_EQ(fate_near({{2.84, -0.15, 0.06}}, {wall}, 2.80, -0.15),
              LegClusterFate::kPointFeature);
  }
  // 5-6 beams on the stub, each within 0.025 m of the line with 0.01 m of noise: almost always.
  EXPECT_GE(stubs_on_line, 17);
}

// A leg-sized object on a corridor's wall (a fire extinguisher: radius 8 cm, 4 cm from the
// wall), seen along the wall, is no person by itself; a leg 0.4 m in front of the same wall is
// one. At 0.35 degrees: at 0.9 this cast scene has no leg-like cluster there to begin with (the
// world's corridor, with its sensor model, does: docs/perception.md, "World scenarios").
TEST(SegmenterPeopleTest, ALegSizedObjectOnAWallIsNoPerson) {
  const WallSegment wall = {-1.0, 1.0, 6.0, 1.0};
  for (double spacing_deg : {0.35}) {
    SCOPED_TRACE(testing::Message() << spacing_deg << " degrees");
    int on_wall = 0;
    int on_wall_without_rule = 0;
    int in_front = 0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      std::mt19937_64 rng(seed);
      const auto people_of = [&](const Circle& circle, double clearance_m) {
        const TestScan scan =
            CastScene({circle}, {wall}, Angles(spacing_deg), 12.0, 0.01, 0.0, &rng);
        SegmenterOptions options;
        options.person.single_leg_surface_clearance_m = clearance_m;
        Segmenter segmenter(options);
        segmenter.Segment(scan.View());
        EXPECT_FALSE(segmenter.lines().empty());
        return static_cast<int>(segmenter.people().size());
      };
      const double clearance_m = 0.2;
      on_wall += people_of({2.5, 0.88, 0.08}, clearance_m);
      on_wall_without_rule += people_of({2.5, 0.88, 0.08}, 0.0);
      in_front += people_of({2.5, 0.6, 0.06}, clearance_m);
    }
    EXPECT_EQ(on_wall, 0);
    EXPECT_GE(on_wall_without_rule, 5);  // it does look like a leg
    EXPECT_GE(in_front, 8);
  }
}

// A wall that drops beams (two in a row every six: no return) shows as a row of short pieces
// with nothing between them; they make no person. Two legs with no return around them (the
// background out of range) are still one.
TEST(SegmenterPeopleTest, PiecesOfAWallBetweenDropoutsAreNoPeople) {
  int people_with_rule = 0;
  int people_without_rule = 0;
  int legs_in_the_open = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    TestScan wall = CastScene({}, {{3.0, -1.0, 3.0, 1.0}}, Angles(0.9), 12.0, 0.01, 0.0, &rng);
    for (size_t i = 0; i < wall.size(); ++i) {
      if (i % 6 >= 4) wall.valid[i] = 0;
    }
    for (bool rule : {true, false}) {
      SegmenterOptions options;
      options.person.separate_dropout_pieces = rule;
      Segmenter segmenter(options);
      segmenter.Segment(wall.View());
      (rule ? people_with_rule : people_without_rule) +=
          static_cast<int>(segmenter.people().size());
    }
    const TestScan legs =
        CastScene({{2.0, 0.15, 0.06}, {2.0, -0.15, 0.06}}, {}, Angles(0.9), 12.0, 0.01, 0.0, &rng);
    Segmenter segmenter(SegmenterOptions{});
    segmenter.Segment(legs.View());
    legs_in_the_open += segmenter.people().size() == 1 && segmenter.people()[0].num_legs == 2;
  }
  EXPECT_GE(people_without_rule, 2);  // some pieces do look like legs
  EXPECT_EQ(people_with_rule, 0);
  EXPECT_GE(legs_in_the_open, 9);
}

// Chair legs (radius 1.5 cm, four at the corners of 0.45 m) at 0.35 degrees: no person.
TEST(SegmenterPeopleTest, ChairLegsAreNotPeople) {
  int people = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    const std::vector<Circle> chair = {
        {1.8, 0.2, 0.015}, {2.25, 0.2, 0.015}, {1.8, -0.25, 0.015}, {2.25, -0.25, 0.015}};
    const TestScan scan =
        CastScene(chair, {{5.0, -4.0, 5.0, 4.0}}, Angles(0.35), 12.0, 0.01, 0.0, &rng);
    Segmenter segmenter(SegmenterOptions{});
    segmenter.Segment(scan.View());
    people += static_cast<int>(segmenter.people().size());
  }
  EXPECT_EQ(people, 0);
}

// Mixed pixels at the edges of a leg in front of a far wall are rejected and counted; the leg
// is still one point feature.
TEST(SegmenterPeopleTest, MixedPixelsAreRejectedAndCounted) {
  int64_t mixed = 0;
  int64_t edges = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    const TestScan scan = CastScene({{2.0, 0.0, 0.06}}, {{6.0, -5.0, 6.0, 5.0}}, Angles(0.35),
                                    12.0, 0.005, 0.0, &rng, /*mixed_probability=*/1.0);
    Segmenter segmenter(SegmenterOptions{});
    const std::vector<Feature>& features = segmenter.Segment(scan.View());
    ASSERT_EQ(features.size(), 1u) << seed;
    mixed += segmenter.stats().beams_mixed_pixel;
    edges += segmenter.stats().depth_edges;
  }
  EXPECT_GE(mixed, 5);   // about one per scan (the mixed range may land near the leg)
  EXPECT_EQ(edges, 20);  // two depth edges per scan, each counted once
}

}  // namespace
}  // namespace slammtt
