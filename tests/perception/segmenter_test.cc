// The segmenter on clean scenes and on every kind of messy scan a real sensor produces
// (issue item 2): each case has a defined result, nothing crashes, nothing is NaN.
#include "perception/segmenter.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/angle.h"
#include "tests/perception/synthetic_scan.h"

namespace slammtt {
namespace {

using testing_support::CastScan;
using testing_support::Circle;
using testing_support::EvenAngles;
using testing_support::TestScan;

constexpr double kDeg = M_PI / 180.0;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// RPLIDAR-like 360-degree scan: 400 beams (0.9 deg), starting at 0, angles in [0, 2 pi).
std::vector<double> RplidarAngles() { return EvenAngles(0.0, 2.0 * M_PI, 400, true); }

void ExpectSane(const std::vector<Feature>& features) {
  for (const Feature& f : features) {
    EXPECT_TRUE(std::isfinite(f.range_m) && f.range_m > 0.0);
    EXPECT_TRUE(std::isfinite(f.bearing_rad));
    EXPECT_GT(f.bearing_rad, -M_PI);
    EXPECT_LE(f.bearing_rad, M_PI);
    EXPECT_TRUE(std::isfinite(f.width_m) && f.width_m >= 0.0);
    EXPECT_GE(f.num_points, 1);
    EXPECT_TRUE(f.covariance.allFinite());
    EXPECT_DOUBLE_EQ(f.covariance(0, 1), f.covariance(1, 0));
    EXPECT_GT(f.covariance(0, 0), 0.0);
    EXPECT_GT(f.covariance(1, 1), 0.0);
    EXPECT_GT(f.covariance.determinant(), 0.0);
  }
}

double CentreError(const Feature& f, const Circle& c) {
  return std::hypot(f.range_m * std::cos(f.bearing_rad) - c.x_m,
                    f.range_m * std::sin(f.bearing_rad) - c.y_m);
}

// Features, each matched to the circle whose centre is nearest.
void ExpectOneFeaturePerCircle(const std::vector<Feature>& features,
                               const std::vector<Circle>& circles, double tolerance_m) {
  ASSERT_EQ(features.size(), circles.size());
  for (const Circle& c : circles) {
    double best = 1e9;
    for (const Feature& f : features) best = std::min(best, CentreError(f, c));
    EXPECT_LT(best, tolerance_m) << "circle at " << c.x_m << ", " << c.y_m;
  }
}

const std::vector<Circle> kScene = {
    {2.0, 0.5, 0.2}, {-1.5, 2.5, 0.25}, {0.5, -3.0, 0.15}, {-3.0, -1.0, 0.3}, {4.0, 3.0, 0.2}};

TEST(SegmenterTest, CleanScanGivesOneFeaturePerObject) {
  const TestScan scan = CastScan(kScene, RplidarAngles());
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ExpectSane(features);
  ExpectOneFeaturePerCircle(features, kScene, 0.03);
  // Increasing bearing.
  for (size_t i = 1; i < features.size(); ++i) {
    EXPECT_LT(features[i - 1].bearing_rad, features[i].bearing_rad);
  }
  const SegmentationStats& stats = segmenter.stats();
  EXPECT_EQ(stats.beams, 400);
  EXPECT_EQ(stats.features, 5);
  EXPECT_EQ(stats.clusters, 5);
  EXPECT_FALSE(stats.beams_were_sorted);
  int beams_on_objects = 0;
  for (const Feature& f : features) beams_on_objects += f.num_points;
  EXPECT_EQ(stats.beams_used, beams_on_objects);
  EXPECT_EQ(stats.beams_flagged_invalid, 400 - beams_on_objects);
  for (size_t i = 0; i < kScene.size(); ++i) {
    double best = 1e9;
    int points = 0;
    for (const Feature& f : features) {
      if (CentreError(f, kScene[i]) < best) {
        best = CentreError(f, kScene[i]);
        points = f.num_points;
      }
    }
    EXPECT_EQ(points, testing_support::BeamsOn(kScene, i, RplidarAngles()));
  }
}

TEST(SegmenterTest, SameScanTwiceGivesIdenticalFeatures) {
  std::mt19937_64 rng(5);
  const TestScan scan = CastScan(kScene, RplidarAngles(), 12.0, 0.02, &rng);
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature> first = segmenter.Segment(scan.View());
  const std::vector<Feature> second = segmenter.Segment(scan.View());
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].range_m, second[i].range_m);
    EXPECT_EQ(first[i].bearing_rad, second[i].bearing_rad);
    EXPECT_EQ(first[i].covariance, second[i].covariance);
  }
}

// RPLIDAR reports distance 0 for no return; the driver flags it invalid. A beam flagged valid
// with range 0 is treated the same way.
TEST(SegmenterTest, InvalidBeamsAreDroppedAndCounted) {
  TestScan scan = CastScan(kScene, RplidarAngles());
  size_t flagged = 0;
  for (int8_t v : scan.valid) flagged += (v == 0);
  // Flag three beams valid although they read 0 m.
  int zero_but_valid = 0;
  for (size_t i = 0; i < scan.size() && zero_but_valid < 3; ++i) {
    if (scan.valid[i] == 0) {
      scan.valid[i] = 1;
      ++zero_but_valid;
    }
  }
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ExpectOneFeaturePerCircle(features, kScene, 0.03);
  EXPECT_EQ(segmenter.stats().beams_flagged_invalid, static_cast<int64_t>(flagged) - 3);
  EXPECT_EQ(segmenter.stats().beams_out_of_range, 3);
}

// One dropped beam inside an object does not split it: eq. 15 with the actual angle between
// the valid neighbours allows the larger gap. Two drops in a row (more than max_dropped_beams)
// do.
TEST(SegmenterTest, DroppedBeamInsideAnObjectDoesNotSplitIt) {
  const std::vector<Circle> wide = {{1.5, 0.0, 0.3}};  // about 23 beams at 0.9 deg
  const std::vector<double> angles = RplidarAngles();
  TestScan scan = CastScan(wide, angles);
  std::vector<size_t> hits;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (scan.valid[i]) hits.push_back(i);
  }
  ASSERT_GT(hits.size(), 15u);
  // The object straddles the 0/2 pi seam of this scan: pick beams inside it by angle.
  std::sort(hits.begin(), hits.end(), [&](size_t a, size_t b) {
    return WrapAngle(angles[a]) < WrapAngle(angles[b]);
  });
  const size_t middle = hits[hits.size() / 2];
  scan.valid[middle] = 0;
  Segmenter segmenter(SegmenterOptions{});
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 1u);
  // The same with the beam NaN instead of flagged.
  scan.valid[middle] = 1;
  scan.range_m[middle] = kNaN;
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 1u);
  EXPECT_EQ(segmenter.stats().beams_non_finite, 1);
  // Two consecutive drops (more than max_dropped_beams = 1, although the 2.7-degree gap is
  // within max_beam_gap): two features; allowing two drops joins them again.
  scan.range_m[middle] = scan.range_m[hits[hits.size() / 2 - 1]];
  scan.valid[middle] = 0;
  scan.valid[hits[hits.size() / 2 + 1]] = 0;
  const std::vector<Feature>& split = segmenter.Segment(scan.View());
  EXPECT_EQ(split.size(), 2u);
  ExpectSane(split);
  SegmenterOptions tolerant;
  tolerant.max_dropped_beams = 2;
  Segmenter bridging(tolerant);
  EXPECT_EQ(bridging.Segment(scan.View()).size(), 1u);
  // Six consecutive drops (a 6.3-degree gap, beyond max_beam_gap as well): two features.
  for (int k = -3; k <= 2; ++k) {
    scan.valid[hits[static_cast<size_t>(static_cast<int>(hits.size() / 2) + k)]] = 0;
  }
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 2u);
  EXPECT_EQ(bridging.Segment(scan.View()).size(), 2u);
}

// Drops are counted around the seam of a 360-degree scan: the beams before the first usable
// one continue the run after the last usable one.
TEST(SegmenterTest, DroppedBeamsAreCountedAcrossTheSeam) {
  const std::vector<Circle> post = {{2.0, 0.0, 0.3}};  // straddles angle 0 = the scan's start
  TestScan scan = CastScan(post, RplidarAngles());
  ASSERT_TRUE(scan.valid[0] && scan.valid[399] && scan.valid[398] && scan.valid[1]);
  Segmenter segmenter(SegmenterOptions{});
  scan.valid[0] = 0;  // one drop, at the start
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 1u);
  scan.valid[0] = 1;
  scan.valid[399] = 0;  // one drop, at the end
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 1u);
  scan.valid[0] = 0;  // the last and the first beam: a run of two across the seam
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  EXPECT_EQ(features.size(), 2u);
  ExpectSane(features);
}

// The RPLIDAR A2 in standard mode gives about 200 beams per revolution (1.8 degrees): objects
// are still whole, because gaps are counted in beams, not degrees.
TEST(SegmenterTest, CoarseScansAreNotCutByGapLimits) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> jitter(-0.3 * kDeg, 0.3 * kDeg);
  std::vector<double> angles = EvenAngles(0.0, 2.0 * M_PI, 200, true);
  for (double& a : angles) a += jitter(rng);
  const std::vector<Circle> near = {{1.5, 0.3, 0.25}, {-1.0, 1.2, 0.2}, {0.2, -1.8, 0.3}};
  const TestScan scan = CastScan(near, angles, 12.0, 0.01, &rng);
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ExpectOneFeaturePerCircle(features, near, 0.06);
  for (size_t i = 0; i < near.size(); ++i) {
    EXPECT_GE(testing_support::BeamsOn(near, i, angles), 8);
  }
}

// A clockwise scan (the RPLIDAR's order in our CCW frame) is reversed, not sorted: the same
// features as the CCW scan, and dropped beams are still counted (two in a row split).
TEST(SegmenterTest, ClockwiseScansAreReversedWithTheirGapCounts) {
  std::mt19937_64 rng(21);
  TestScan ccw = CastScan(kScene, RplidarAngles(), 12.0, 0.01, &rng);
  std::vector<size_t> hits;  // beams on the first object of kScene
  for (size_t i = 0; i < ccw.size(); ++i) {
    if (ccw.valid[i] && testing_support::RayCircle(ccw.angle_rad[i], kScene[0]) > 0.0) {
      hits.push_back(i);
    }
  }
  ASSERT_GT(hits.size(), 8u);
  ccw.valid[hits[hits.size() / 2]] = 0;  // one dropout: bridged
  TestScan cw = ccw;
  std::reverse(cw.angle_rad.begin(), cw.angle_rad.end());
  std::reverse(cw.range_m.begin(), cw.range_m.end());
  std::reverse(cw.valid.begin(), cw.valid.end());
  Segmenter a(SegmenterOptions{});
  Segmenter b(SegmenterOptions{});
  const std::vector<Feature>& fa = a.Segment(ccw.View());
  const std::vector<Feature>& fb = b.Segment(cw.View());
  EXPECT_FALSE(b.stats().beams_were_sorted);
  EXPECT_TRUE(b.stats().beams_were_reversed);
  EXPECT_FALSE(a.stats().beams_were_reversed);
  ASSERT_EQ(fa.size(), kScene.size());
  ASSERT_EQ(fb.size(), kScene.size());
  for (size_t i = 0; i < fa.size(); ++i) {
    EXPECT_EQ(fa[i].num_points, fb[i].num_points);
    EXPECT_NEAR(fa[i].range_m, fb[i].range_m, 1e-9);
    EXPECT_NEAR(fa[i].bearing_rad, fb[i].bearing_rad, 1e-9);
  }
  // A second dropout next to the first one: two in a row split the object, CCW and CW alike.
  const size_t second = hits[hits.size() / 2 + 1];
  ccw.valid[second] = 0;
  cw.valid[cw.size() - 1 - second] = 0;
  EXPECT_EQ(a.Segment(ccw.View()).size(), kScene.size() + 1);
  EXPECT_EQ(b.Segment(cw.View()).size(), kScene.size() + 1);
}

// Beams out of order are sorted, and the gaps are still counted in angle order: two drops in a
// row split the post whether or not the scan needed sorting.
TEST(SegmenterTest, SortedScansKeepTheirGapCounts) {
  const std::vector<Circle> post = {{1.5, 1.5, 0.3}};
  TestScan scan = CastScan(post, RplidarAngles());
  std::vector<size_t> hits;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (scan.valid[i]) hits.push_back(i);
  }
  scan.valid[hits[hits.size() / 2]] = 0;
  scan.valid[hits[hits.size() / 2 + 1]] = 0;  // two drops: 2.7 degrees
  Segmenter segmenter(SegmenterOptions{});
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 2u);
  EXPECT_FALSE(segmenter.stats().beams_were_sorted);
  // Shuffle everything.
  std::mt19937_64 rng(8);
  for (size_t i = scan.size(); i > 1; --i) {
    const size_t j = static_cast<size_t>(rng() % i);
    std::swap(scan.angle_rad[i - 1], scan.angle_rad[j]);
    std::swap(scan.range_m[i - 1], scan.range_m[j]);
    std::swap(scan.valid[i - 1], scan.valid[j]);
  }
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), 2u);
  EXPECT_TRUE(segmenter.stats().beams_were_sorted);
}

// RPLIDAR express mode in our frame: clockwise, and each sample's angle corrected by up to 2
// degrees, so that neighbours often swap. The features equal those of the clean CCW scan; one
// dropout inside an object is bridged, two split it.
TEST(SegmenterTest, ExpressModeLikeScansAreReorderedKeepingGaps) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> correction(0.0, 2.0 * kDeg);
  const std::vector<double> clean = RplidarAngles();
  std::vector<double> angles;
  for (size_t i = 0; i < clean.size(); ++i) {
    angles.push_back(-clean[i] + correction(rng));  // clockwise from 0, then corrected
  }
  TestScan scan = CastScan(kScene, angles, 12.0, 0.01, &rng);
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature> features = segmenter.Segment(scan.View());
  EXPECT_TRUE(segmenter.stats().beams_were_reversed);
  EXPECT_TRUE(segmenter.stats().beams_were_sorted);
  ExpectOneFeaturePerCircle(features, kScene, 0.05);
  // Drop beams on the first object, in angle order.
  std::vector<size_t> on_first;
  for (size_t i = 0; i < scan.size(); ++i) {
    if (scan.valid[i] && testing_support::RayCircle(angles[i], kScene[0]) > 0.0) {
      on_first.push_back(i);
    }
  }
  std::sort(on_first.begin(), on_first.end(),
            [&](size_t a, size_t b) { return angles[a] < angles[b]; });
  ASSERT_GT(on_first.size(), 8u);
  scan.valid[on_first[on_first.size() / 2]] = 0;
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), kScene.size());
  scan.valid[on_first[on_first.size() / 2 + 1]] = 0;
  EXPECT_EQ(segmenter.Segment(scan.View()).size(), kScene.size() + 1);
}

TEST(SegmenterTest, NonFiniteAnglesAndRangesAreDroppedAndCounted) {
  TestScan scan = CastScan(kScene, RplidarAngles());
  // Poison beams that are not on an object (so the objects stay whole), flagged valid.
  int poisoned = 0;
  const float poison[] = {kNaN, kInf, -kInf};
  for (size_t i = 0; i < scan.size() && poisoned < 12; ++i) {
    if (scan.valid[i] != 0) continue;
    scan.valid[i] = 1;
    if (poisoned % 2 == 0) {
      scan.range_m[i] = poison[poisoned % 3];
    } else {
      scan.angle_rad[i] = poison[poisoned % 3];
      scan.range_m[i] = 2.0f;
    }
    ++poisoned;
  }
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ExpectSane(features);
  ExpectOneFeaturePerCircle(features, kScene, 0.03);
  EXPECT_EQ(segmenter.stats().beams_non_finite, 12);
}

TEST(SegmenterTest, OutOfRangeBeamsAreDroppedUsingTheTighterLimit) {
  TestScan scan = CastScan(kScene, RplidarAngles(), 30.0);
  scan.range_max_m = 30.0;
  SegmenterOptions options;
  options.max_range_m = 3.0;  // objects at 2.06, 2.9, 3.04, 3.16, 5 m: two stay (centres)
  Segmenter segmenter(options);
  const std::vector<Feature>& near = segmenter.Segment(scan.View());
  ExpectSane(near);
  for (const Feature& f : near) {
    EXPECT_LT(f.range_m - f.radius_m, 3.0);
  }
  EXPECT_GT(segmenter.stats().beams_out_of_range, 0);
  // The scan's own limit applies too, and a nonsense sensor limit is ignored.
  scan.range_max_m = 2.5;
  Segmenter unlimited(SegmenterOptions{});
  const std::vector<Feature> by_sensor = unlimited.Segment(scan.View());
  ASSERT_EQ(by_sensor.size(), 1u);
  EXPECT_LT(CentreError(by_sensor[0], kScene[0]), 0.03);
  scan.range_max_m = std::nan("");
  scan.range_min_m = -1.0;
  EXPECT_EQ(unlimited.Segment(scan.View()).size(), kScene.size());
  // Below the minimum range.
  scan.range_min_m = 2.5;
  EXPECT_EQ(unlimited.Segment(scan.View()).size(), kScene.size() - 1);
}

TEST(SegmenterTest, UnevenlySpacedBeamsGiveTheSameObjects) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3 * kDeg, 0.3 * kDeg);
  std::vector<double> angles = RplidarAngles();
  for (double& a : angles) a += jitter(rng);
  const TestScan scan = CastScan(kScene, angles);
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ExpectSane(features);
  ExpectOneFeaturePerCircle(features, kScene, 0.04);
}

// Shuffled beams are sorted (stably) and give exactly the features of the ordered scan.
TEST(SegmenterTest, UnsortedBeamsGiveTheSameFeatures) {
  std::mt19937_64 rng(9);
  const TestScan ordered = CastScan(kScene, RplidarAngles(), 12.0, 0.02, &rng);
  TestScan shuffled = ordered;
  std::vector<size_t> order(ordered.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  for (size_t i = 0; i < order.size(); ++i) {
    shuffled.angle_rad[i] = ordered.angle_rad[order[i]];
    shuffled.range_m[i] = ordered.range_m[order[i]];
    shuffled.valid[i] = ordered.valid[order[i]];
  }
  Segmenter a(SegmenterOptions{});
  Segmenter b(SegmenterOptions{});
  const std::vector<Feature>& fa = a.Segment(ordered.View());
  const std::vector<Feature>& fb = b.Segment(shuffled.View());
  EXPECT_FALSE(a.stats().beams_were_sorted);
  EXPECT_TRUE(b.stats().beams_were_sorted);
  ASSERT_EQ(fa.size(), fb.size());
  for (size_t i = 0; i < fa.size(); ++i) {
    EXPECT_NEAR(fa[i].range_m, fb[i].range_m, 1e-9);
    EXPECT_NEAR(fa[i].bearing_rad, fb[i].bearing_rad, 1e-9);
    EXPECT_EQ(fa[i].num_points, fb[i].num_points);
    EXPECT_EQ(order[static_cast<size_t>(fb[i].first_beam_index)],
              static_cast<size_t>(fa[i].first_beam_index));
  }
}

// The same direction twice (RPLIDAR repeats angles): the nearer return is kept, counted, and the
// object is not cut in two by the pair.
TEST(SegmenterTest, DuplicatedAnglesKeepTheNearerReturn) {
  const std::vector<Circle> post = {{3.0, 0.0, 0.25}};
  TestScan scan = CastScan(post, RplidarAngles());
  Segmenter reference_segmenter(SegmenterOptions{});
  const std::vector<Feature> reference = reference_segmenter.Segment(scan.View());
  ASSERT_EQ(reference.size(), 1u);
  // Append every beam on the post again with a far range (a late return from the wall behind)
  // and one exact copy.
  const size_t n = scan.size();
  int copies = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!scan.valid[i]) continue;
    scan.angle_rad.push_back(scan.angle_rad[i]);
    scan.range_m.push_back(copies == 0 ? scan.range_m[i] : 8.0f);
    scan.valid.push_back(1);
    ++copies;
  }
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(segmenter.stats().beams_duplicate, copies);
  EXPECT_TRUE(segmenter.stats().beams_were_sorted);
  EXPECT_EQ(features[0].num_points, reference[0].num_points);
  EXPECT_NEAR(features[0].range_m, reference[0].range_m, 1e-9);
  EXPECT_NEAR(features[0].bearing_rad, reference[0].bearing_rad, 1e-9);
}

// A 360-degree scan that starts in the middle of an object: the cluster across the seam is one
// feature, equal to the one found when the scan starts elsewhere.
TEST(SegmenterTest, ObjectAcrossTheSeamOfA360ScanIsOneFeature) {
  const std::vector<Circle> scene = {{2.5, 0.0, 0.3}, {0.0, 2.0, 0.2}};  // the first at 0 rad
  // Angles in [0, 2 pi): the object at bearing 0 is hit by the first and the last beams.
  const TestScan seam = CastScan(scene, RplidarAngles());
  ASSERT_TRUE(seam.valid.front() && seam.valid.back());
  // The same scene with a scan that starts at -pi (the object in the middle).
  const TestScan middle = CastScan(scene, EvenAngles(-M_PI, 2.0 * M_PI, 400, true));
  Segmenter a(SegmenterOptions{});
  Segmenter b(SegmenterOptions{});
  const std::vector<Feature>& fa = a.Segment(seam.View());
  const std::vector<Feature>& fb = b.Segment(middle.View());
  ASSERT_EQ(fa.size(), 2u);
  ASSERT_EQ(fb.size(), 2u);
  EXPECT_EQ(a.stats().clusters_across_seam, 1);
  EXPECT_EQ(b.stats().clusters_across_seam, 0);
  EXPECT_FALSE(a.stats().beams_were_sorted);  // [0, 2 pi) is circular order: no sort needed
  const Feature& across = std::abs(fa[0].bearing_rad) < 0.5 ? fa[0] : fa[1];
  EXPECT_GT(across.first_beam_index, across.last_beam_index);  // runs over the seam
  EXPECT_EQ(across.last_beam_index + 1 + (400 - across.first_beam_index), across.num_points);
  ExpectOneFeaturePerCircle(fa, scene, 0.03);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(fa[i].num_points, fb[i].num_points);
    EXPECT_NEAR(fa[i].range_m, fb[i].range_m, 1e-6);
    EXPECT_NEAR(fa[i].bearing_rad, fb[i].bearing_rad, 1e-6);
  }
}

// A 180-degree scan does not wrap: two objects at its two ends, at the same range, stay two
// features even though their points are "neighbours" around the circle.
TEST(SegmenterTest, A180DegreeScanDoesNotWrap) {
  const std::vector<double> angles = EvenAngles(-0.5 * M_PI, M_PI, 181, false);
  // Objects just inside both ends of the field of view, at the same distance behind the sensor
  // line (y = -+ 2 m), each hit by several beams.
  const std::vector<Circle> scene = {{0.3, -2.0, 0.3}, {0.3, 2.0, 0.3}};
  const TestScan scan = CastScan(scene, angles);
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature>& features = segmenter.Segment(scan.View());
  ASSERT_EQ(features.size(), 2u);
  EXPECT_EQ(segmenter.stats().clusters_across_seam, 0);
  EXPECT_LT(features[0].bearing_rad, -1.0);
  EXPECT_GT(features[1].bearing_rad, 1.0);
}

// A scan covering all directions with a surface all around (robot inside a round room or a
// ring of people shoulder to shoulder) has no breakpoint: that one cluster surrounds the sensor
// and has no centre, so no point feature: structure (its chords are lines), or, without line
// extraction, counted as too wide.
TEST(SegmenterTest, SurroundingRingGivesNoFeature) {
  TestScan scan;
  for (double a : RplidarAngles()) {
    scan.angle_rad.push_back(static_cast<float>(a));
    scan.range_m.push_back(3.0f);
    scan.valid.push_back(1);
  }
  Segmenter segmenter(SegmenterOptions{});
  EXPECT_TRUE(segmenter.Segment(scan.View()).empty());
  EXPECT_EQ(segmenter.stats().clusters, 1);
  EXPECT_EQ(segmenter.stats().clusters_structure, 1);
  EXPECT_GT(segmenter.lines().size(), 3u);
  SegmenterOptions no_lines;
  no_lines.extract_lines = false;
  Segmenter plain(no_lines);
  EXPECT_TRUE(plain.Segment(scan.View()).empty());
  EXPECT_EQ(plain.stats().clusters_too_wide, 1);
  EXPECT_TRUE(plain.lines().empty());
}

TEST(SegmenterTest, WallsAndSmallClustersAreNotFeatures) {
  TestScan scan;
  // A wall 2 m ahead from -40 to 40 degrees (2.9 m wide), and two isolated beams.
  for (int i = -44; i <= 44; ++i) {
    const double a = i * 0.9 * kDeg;
    scan.angle_rad.push_back(static_cast<float>(a));
    scan.range_m.push_back(static_cast<float>(2.0 / std::cos(a)));
    scan.valid.push_back(1);
  }
  scan.angle_rad.insert(scan.angle_rad.end(), {1.5f, 1.6f});
  scan.range_m.insert(scan.range_m.end(), {4.0f, 4.0f});
  scan.valid.insert(scan.valid.end(), {1, 1});
  Segmenter segmenter(SegmenterOptions{});
  EXPECT_TRUE(segmenter.Segment(scan.View()).empty());
  EXPECT_EQ(segmenter.stats().clusters, 3);
  EXPECT_EQ(segmenter.stats().clusters_too_wide, 0);
  EXPECT_EQ(segmenter.stats().clusters_too_few_points, 2);
  EXPECT_EQ(segmenter.stats().beams_isolated, 2);
  // The wall is one line feature: 2 m ahead, normal along x.
  ASSERT_EQ(segmenter.lines().size(), 1u);
  EXPECT_NEAR(segmenter.lines()[0].rho_m, 2.0, 1e-6);
  EXPECT_NEAR(segmenter.lines()[0].alpha_rad, 0.0, 1e-6);
  EXPECT_EQ(segmenter.lines()[0].num_points, 89);
  EXPECT_EQ(segmenter.stats().beams_on_lines, 89);
  // Without line extraction, the paper's algorithm: the wall is too wide for a point feature.
  SegmenterOptions no_lines;
  no_lines.extract_lines = false;
  Segmenter plain(no_lines);
  EXPECT_TRUE(plain.Segment(scan.View()).empty());
  EXPECT_EQ(plain.stats().clusters_too_wide, 1);
}

TEST(SegmenterTest, ScansWithNothingUsableGiveNoFeatures) {
  Segmenter segmenter(SegmenterOptions{});
  // No beam at all, and null arrays.
  EXPECT_TRUE(segmenter.Segment(ScanView{}).empty());
  ScanView broken;
  broken.num_beams = 5;  // arrays missing: every beam counts as non-finite
  EXPECT_TRUE(segmenter.Segment(broken).empty());
  EXPECT_EQ(segmenter.stats().beams_non_finite, 5);
  // Every beam flagged invalid.
  TestScan dark = CastScan({}, RplidarAngles());
  EXPECT_TRUE(segmenter.Segment(dark.View()).empty());
  EXPECT_EQ(segmenter.stats().beams_flagged_invalid, 400);
  EXPECT_EQ(segmenter.stats().beams_used, 0);
  // Every beam NaN.
  for (float& r : dark.range_m) r = kNaN;
  for (int8_t& v : dark.valid) v = 1;
  EXPECT_TRUE(segmenter.Segment(dark.View()).empty());
  EXPECT_EQ(segmenter.stats().beams_non_finite, 400);
}

TEST(SegmenterTest, OneOrTwoBeamsAndIdenticalAngles) {
  SegmenterOptions options;
  options.min_points = 1;
  Segmenter segmenter(options);
  std::vector<float> angle = {0.5f};
  std::vector<float> range = {2.0f};
  const std::vector<Feature> one = segmenter.Segment(MakeScanView(angle, range));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_FLOAT_EQ(static_cast<float>(one[0].range_m), 2.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(one[0].bearing_rad), 0.5f);
  ExpectSane(one);
  angle = {0.5f, 0.51f};
  range = {2.0f, 2.0f};
  const std::vector<Feature> two = segmenter.Segment(MakeScanView(angle, range));
  ASSERT_EQ(two.size(), 1u);
  EXPECT_EQ(two[0].num_points, 2);
  ExpectSane(two);
  // Every beam at the same angle: one direction, the nearest return.
  angle = {1.0f, 1.0f, 1.0f, 1.0f};
  range = {3.0f, 2.0f, 2.5f, 4.0f};
  const std::vector<Feature> same = segmenter.Segment(MakeScanView(angle, range));
  ASSERT_EQ(same.size(), 1u);
  EXPECT_FLOAT_EQ(static_cast<float>(same[0].range_m), 2.0f);
  EXPECT_EQ(segmenter.stats().beams_duplicate, 3);
}

// Angles in any turn ([0, 2 pi), (-pi, pi], several turns away) mean the same directions.
TEST(SegmenterTest, AnglesAreWrapped) {
  const TestScan base = CastScan(kScene, EvenAngles(-M_PI, 2.0 * M_PI, 400, true));
  Segmenter segmenter(SegmenterOptions{});
  const std::vector<Feature> reference = segmenter.Segment(base.View());
  for (double turns : {1.0, -1.0, 7.0, -13.0}) {
    TestScan shifted = base;
    for (float& a : shifted.angle_rad) {
      a = static_cast<float>(static_cast<double>(a) + turns * 2.0 * M_PI);
    }
    const std::vector<Feature> f = segmenter.Segment(shifted.View());
    ASSERT_EQ(f.size(), reference.size()) << turns;
    ExpectSane(f);
    for (size_t i = 0; i < f.size(); ++i) {
      // float angles lose precision several turns out: 1e-5 rad at 13 turns.
      EXPECT_NEAR(f[i].bearing_rad, reference[i].bearing_rad, 2e-5) << turns;
    }
  }
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), M_PI);
  EXPECT_DOUBLE_EQ(WrapAngle(-M_PI), M_PI);
  EXPECT_NEAR(WrapAngle(3.0 * M_PI + 0.1), -M_PI + 0.1, 1e-12);
  EXPECT_NEAR(WrapAngle(1e6), std::remainder(1e6, 2.0 * M_PI), 1e-9);
}

// Random junk: random angles (some NaN), random ranges (some negative, zero, huge, inf),
// random validity. The result is always sane.
TEST(SegmenterTest, RandomGarbageNeverBreaksIt) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<float> any_angle(-20.0f, 20.0f);
  std::uniform_real_distribution<float> any_range(-1.0f, 40.0f);
  std::uniform_int_distribution<int> pick(0, 19);
  std::uniform_int_distribution<int> size(0, 1200);
  Segmenter segmenter(SegmenterOptions{});
  int64_t total_features = 0;
  for (int trial = 0; trial < 300; ++trial) {
    TestScan scan;
    const int n = size(rng);
    const bool clustered = trial % 2 == 0;  // half the scans sorted-ish with smooth ranges
    float smooth = 3.0f;
    for (int i = 0; i < n; ++i) {
      float a = clustered ? static_cast<float>(i) * 0.015f : any_angle(rng);
      float r = clustered ? (smooth += 0.02f * static_cast<float>(pick(rng) - 10)) : any_range(rng);
      const int special = pick(rng);
      if (special == 0) a = kNaN;
      if (special == 1) r = kInf;
      if (special == 2) r = 0.0f;
      if (special == 3) r = 1e30f;
      scan.angle_rad.push_back(a);
      scan.range_m.push_back(r);
      scan.valid.push_back(static_cast<int8_t>(pick(rng) == 4 ? 0 : (pick(rng) == 5 ? 7 : 1)));
    }
    scan.range_max_m = 30.0;
    const std::vector<Feature>& features = segmenter.Segment(scan.View());
    ExpectSane(features);
    const SegmentationStats& s = segmenter.stats();
    EXPECT_EQ(s.beams, n);
    EXPECT_EQ(s.beams_used + s.beams_flagged_invalid + s.beams_non_finite + s.beams_out_of_range +
                  s.beams_duplicate,
              n);
    total_features += s.features;
  }
  EXPECT_GT(total_features, 100);  // the smooth scans did produce features
}

TEST(SegmenterTest, BadOptionsAreRejectedWithTheFieldName) {
  SegmenterOptions options;
  options.lambda_rad = 100.0 * kDeg;
  EXPECT_EQ(CheckSegmenterOptions(options), "lambda_deg = 100: must be in (0, 90)");
  try {
    Segmenter segmenter(options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lambda_deg"), std::string::npos);
  }
  options = SegmenterOptions{};
  options.sigma_r_m = std::nan("");
  EXPECT_NE(CheckSegmenterOptions(options).find("sigma_r_m"), std::string::npos);
  options = SegmenterOptions{};
  options.max_range_m = 0.0;
  EXPECT_EQ(CheckSegmenterOptions(options), "max_range_m must be > min_range_m");
  options.max_range_m = -std::numeric_limits<double>::infinity();
  EXPECT_NE(CheckSegmenterOptions(options).find("max_range_m"), std::string::npos);
  options = SegmenterOptions{};
  options.min_points = 0;
  EXPECT_NE(CheckSegmenterOptions(options).find("min_points"), std::string::npos);
  options = SegmenterOptions{};
  options.max_dropped_beams = -1;
  EXPECT_NE(CheckSegmenterOptions(options).find("max_dropped_beams"), std::string::npos);
  options = SegmenterOptions{};
  options.bearing_sigma_rad = 0.0;
  EXPECT_EQ(CheckSegmenterOptions(options), "bearing_sigma_deg = 0: must be > 0");
  options = SegmenterOptions{};
  options.person.single_leg_threshold = 1.5;
  EXPECT_EQ(CheckSegmenterOptions(options),
            "person_single_leg_threshold = 1.5: must be in [0, 1]");
  options = SegmenterOptions{};
  options.centre_rule = static_cast<CentreRule>(7);
  EXPECT_EQ(CheckSegmenterOptions(options), "centre_rule is not one of its choices");
  EXPECT_EQ(CheckSegmenterOptions(SegmenterOptions{}), "");
}

}  // namespace
}  // namespace slammtt
