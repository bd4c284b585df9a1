// The geometric features of one cluster that the learned leg classifier (leg_classifier.h)
// reads: ONE implementation, used by the segmenter at run time and by the training program
// (tools/legs) to extract its training set, so that the model sees at run time exactly what it
// saw in training.
//
// The features are those of Arras, Mozos and Burgard ("Using boosted features for the
// detection of people in 2D range data", ICRA 2007, section IV, Table I: f1-f13; f14, the
// speed, needs two scans and is left out), which Leigh, Pineau, Olmedo and Zhang ("Person
// tracking and following with 2D laser scanners", ICRA 2015, section III-A) feed to a random
// forest together with the cluster's distance from the laser. Two cues of the hand-written
// score (leg_likeness.h) are added: the distance between neighbouring beams at the cluster
// (range times beam spacing, so that one model serves a 0.35 and a 0.9 degree scanner: it is
// measured from the cluster, never taken from a sensor's name, and it varies continuously
// with range, so a model cannot tell scanners apart by a spacing value seen in training) and
// the convexity towards the sensor. Per cluster of n points p_1..p_n (counter-clockwise),
// centroid c:
//
//   kPoints              n (f1)
//   kRange               mean range of the points [m] (Leigh et al.'s distance to the laser)
//   kBeamGap             mean range times the mean angle between neighbouring beams [m]
//                        (a cluster of one point: the scan's spacing near it)
//   kWidth               |p_n - p_1| [m] (f6)
//   kStdDev              sqrt(mean |p_i - c|^2) [m] (f2)
//   kMadMedian           mean |p_i - m|, m the coordinate-wise median point [m] (f3)
//   kJumpBefore          range of the beam just before p_1 minus p_1's range, clamped to
//                        +-kLegJumpCapM; a neighbour without a usable return (no echo, an
//                        invalid or dropped beam) counts as far behind: +kLegJumpCapM (f4, signed:
//                        negative when something nearer hides the cluster's edge)
//   kJumpAfter           the same after p_n (f5)
//   kLineRms             RMS distance of the points from their total-least-squares line [m]
//                        (f7, as an RMS so that it does not grow with n)
//   kCircleRms           RMS distance from the algebraic circle fit (line_extraction.h's
//                        FitCircleKasa) [m] (f8); no circle (fewer than 3 points, collinear):
//                        the line's RMS
//   kCircleRadius        that circle's radius, at most kLegRadiusCapM [m] (f9); no circle: the
//                        cap
//   kBoundaryLength      sum |p_{i+1} - p_i| [m] (f10)
//   kBoundaryRegularity  standard deviation of those distances [m] (f11)
//   kMeanCurvature       mean over interior points of the signed curvature of the circle
//                        through p_{i-1}, p_i, p_{i+1} [1/m], positive when the outline bulges
//                        towards the sensor (f12)
//   kMeanTurn            mean signed angle between p_{i-1}p_i and p_i p_{i+1} [rad], positive
//                        the same way (f13)
//   kConvexity           mean distance in front of the chord p_1 p_n of the middle half of the
//                        points, over half the nominal diameter r (extent + spacing): 0.7 for a
//                        half circle, 0 flat, negative concave (leg_likeness.h)
// Features of a cluster too small to have them (curvature of two points) are 0.
//
// Frames: the cluster's points in any frame whose origin is the sensor (the segmenter turns
// it to the cluster's middle); every feature is invariant to that rotation. Values are float
// (what the model's thresholds compare against), finite for finite input.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "perception/centre_estimation.h"

namespace slammtt {

enum LegFeatureIndex : int {
  kPoints = 0,
  kRange,
  kBeamGap,
  kWidth,
  kStdDev,
  kMadMedian,
  kJumpBefore,
  kJumpAfter,
  kLineRms,
  kCircleRms,
  kCircleRadius,
  kBoundaryLength,
  kBoundaryRegularity,
  kMeanCurvature,
  kMeanTurn,
  kConvexity,
  kNumLegFeatures,
};

// Names as the model file and the documentation spell them, indexed by LegFeatureIndex.
extern const std::array<const char*, kNumLegFeatures> kLegFeatureNames;

using LegFeatureVector = std::array<float, kNumLegFeatures>;

inline constexpr double kLegJumpCapM = 1.0;
inline constexpr double kLegRadiusCapM = 2.0;

// What lies just outside the cluster in angle: the ranges of the beams before its first and
// after its last point. NaN: that beam had no usable return.
struct ClusterSurroundings {
  double range_before_m = std::numeric_limits<double>::quiet_NaN();
  double range_after_m = std::numeric_limits<double>::quiet_NaN();
  // Beam spacing of the scan near the cluster [rad], used for a cluster of one point.
  double scan_spacing_rad = 0.0;
};

// The features of `cluster` (count >= 1, finite positive ranges). Non-finite intermediate
// values (never seen for finite input) become 0, so the vector is always finite.
LegFeatureVector ComputeLegFeatures(const ClusterView& cluster,
                                    const ClusterSurroundings& surroundings);

}  // namespace slammtt
