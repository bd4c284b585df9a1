// People from leg candidates: pairs of legs, or one leg alone, become person features.
//
// A person at the laser's height is two legs (Arras, Mozos, Burgard, ICRA 2007; Leigh et al.,
// ICRA 2015, who pair leg tracks the same way): two leg candidates whose centres are between
// min_leg_separation_m and max_leg_separation_m apart (people's legs are about 0.1-0.6 m apart,
// standing to full stride) are one person, centred at the midpoint of the legs. Pairs are
// taken greedily by increasing separation (ties: lower candidate indices first), each leg in at
// most one person. A leg left over whose leg-likeness reaches single_leg_threshold is a person
// too (the other leg hidden, or both legs in one cluster), centred on that leg with a larger
// covariance. Provisional candidates (two-beam clusters, see Segmenter) only join a pair with a
// candidate that is not provisional, and never make a person alone.
//
// A candidate that may be a piece of a surface (LegCandidate::surface_piece: flat, and no usable
// return on either side, see Segmenter) never makes a person alone, and two such candidates
// are no pair: a flat cluster whose extent is unknown cannot be told from a visible piece of a
// larger surface whose rest gave no return (a wall at grazing incidence, a door frame beside an
// opening, a dark surface); a leg is round. In the world's office scenes (docs/perception.md,
// "World scenarios") such clusters were 40 % of the false one-leg people and no real person.
//
// One-leg centre (PersonDetectionOptions::hidden_leg_centre, off by default: it helps the
// detection figures but costs the estimator's office people MOTA, docs/perception.md "World
// scenarios", item 4; with the scan's SightLines): the
// other leg is somewhere min_leg_separation_m-max_leg_separation_m from the visible one, and
// where the scan sees past a place it is not there. The other leg is taken at the mean of the
// places around the visible leg (a polar grid) that the scan does not see: behind the visible
// leg itself (the other foot in its shadow), behind a nearer object, outside the field of view
// or in a wide gap without returns; the body is the midpoint of the two legs. Without it the
// centre is on the leg, half a stride off (0.17 m at the median, more than the 0.3 m match for
// a walking person at mid-stride: docs/perception.md, "World scenarios").
//
// A one-leg person whose leg has an open edge (the beam beside it gave no usable return, so
// the cluster may go on unseen: a stub of a wall beside an opening or at grazing incidence, a
// corner of furniture) needs single_leg_threshold + single_leg_open_edge_step per open edge.
// Off (0) by default: in the world's office-hokuyo 96 of 97 one-leg people with two open edges
// were false, but real Hokuyos drop the edge beams of legs, and on leg_tracker_demo a step of
// 0.05 already left 97 of 1265 scans without anybody (49 without it; docs/perception.md,
// "World scenarios").
//
// A one-leg person whose leg stands less than single_leg_surface_clearance_m in front of a line
// feature of the scan (LegCandidate::surface_clearance_m: a wall, a side of furniture; the
// distance to the observed extent) is none: the hidden leg must be somewhere, and the visible
// leg's shadow, where it usually is (the other foot behind it from the sensor), ends at the
// surface before there is room for a leg (min_leg_separation_m behind the visible one and a
// leg's radius clear of the surface). Such clusters are objects on the surface: in the world's
// corridor a fire extinguisher on the wall gave 64 of the 185 false people within 4 m, and no
// real one-leg person was within 0.3 m of a line (docs/perception.md, "World scenarios"). Two
// legs in front of a wall are still a person.
//
// With separate_dropout_pieces, a candidate of a dropout run (LegCandidate::dropout_run, set by
// the Segmenter: three or more clusters in a row, each with no usable return on either side,
// nothing but beams without a return between them, and one straight line through all their
// points) makes no person alone and no pair with another of its run: they are pieces of one
// surface that drops beams (a dark or shiny wall, a wall at grazing incidence). Two such
// clusters are left alone: a person's two legs with nothing behind them in range (or blanked,
// as in the extracted leg_tracker bags) look the same. In the world's corridor the end wall
// drops half its beams; its pieces made 50 of the 121 false people within 4 m left by the
// surface-clearance rule, 31 after this one (docs/perception.md, "World scenarios").
//
// With single_leg_open_edge_max_points > 0, a candidate that would be a one-leg person but has
// an open edge (LegCandidate::open_edges) and at most that many points is a stub: no person,
// and the Segmenter drops it from the point features too. Three beams show little of a shape,
// and with no return beside them the cluster may go on unseen (a stub of a wall or a desk side
// beside a dropout); as a point feature its centre would be no better, and one that looks this
// much like a leg would reach the map where a person may stand. Off (0) by default: in the
// world's office (0.9 degrees, within 4 m) it removes 21 of the 93 false people and no matched
// one (precision 0.891 -> 0.913), but the world's legs always have their edge beams and real
// ones do not: at coarse beams real legs pay (positive_4 decimated to every third beam: labelled
// legs in a person 0.530 -> 0.465) and so does the estimator (the corridor's people MOTA, the
// leg_tracker_demo's agreement with the leg pairs; docs/perception.md, "World scenarios", item 7).
//
// Covariance, in Cartesian coordinates and then in range/bearing of the centre (first-order):
//   two legs: (P1 + P2) / 4 + pair_centre_sigma_m^2 I (the body's centre is not exactly the
//             midpoint of the legs);
//   one leg:  P1 + single_leg_offset_sigma_m^2 I (the centre is anywhere within about half a
//             stride of the leg).
// Confidence: sqrt(l1 l2) for a pair, 0.5 l1 for a single leg (l: leg-likeness).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace slammtt {

struct PersonFeature {
  double range_m = 0.0;      // range of the person's centre from the sensor
  double bearing_rad = 0.0;  // bearing of the centre, (-pi, pi]
  // Covariance of (range_m, bearing_rad): [m^2, m rad; m rad, rad^2], positive definite.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  int num_legs = 0;                  // 1 or 2
  int32_t leg_index[2] = {-1, -1};  // indices of the legs in the scan's point features
  double confidence = 0.0;           // in [0, 1]
};

struct LegCandidate {
  double range_m = 0.0;
  double bearing_rad = 0.0;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // of (range_m, bearing_rad)
  double leg_likeness = 0.0;
  bool provisional = false;
  bool surface_piece = false;  // flat, and no usable return on either side
  int open_edges = 0;          // edges (0-2) beside a beam without a usable return
  int num_points = 0;          // beams in the cluster (0: unknown, no rule on it)
  // Distance from the centre to the nearest line feature of the scan (a wall, a side of
  // furniture) that it stands in front of (on the sensor's side); +infinity without one.
  double surface_clearance_m = std::numeric_limits<double>::infinity();
  // Candidates with one value >= 0 are clusters of one straight run of three or more separated
  // only by beams without a usable return, each with none on either side (-1: in no such run).
  int32_t dropout_run = -1;
  int32_t feature_index = -1;  // copied into PersonFeature::leg_index
};

// The scan as lines of sight, to tell where a hidden leg can be: usable beams in increasing
// angle (-pi, pi]. Beams farther apart than max_gap_rad leave their gap unknown.
struct SightLines {
  const double* angle_rad = nullptr;
  const double* range_m = nullptr;
  size_t count = 0;
  double max_gap_rad = 0.0;
  // True when a leg centred at `point` (sensor frame) could be hidden: the beam nearest its
  // bearing returns from more than margin_m in front of it, or the scan has no beam there.
  bool Hides(const Eigen::Vector2d& point, double margin_m) const;
};

struct PersonDetectionOptions {
  double min_leg_separation_m = 0.1;
  double max_leg_separation_m = 0.7;
  double single_leg_threshold = 0.65;
  double pair_centre_sigma_m = 0.05;
  double single_leg_offset_sigma_m = 0.15;
  bool hidden_leg_centre = false;
  // A one-leg person needs this much more leg-likeness per open edge of its leg.
  double single_leg_open_edge_step = 0.0;
  // A one-leg person's leg stands at least this far in front of a line feature of the scan (no
  // room behind it for the hidden leg); 0: no such rule. Off by default, as is
  // separate_dropout_pieces: on the world's corridor they raise the precision (0.2 m and true:
  // 0.801 -> 0.881), but the real estimator's map of the mines recordings moves beyond its
  // floors (tests/python/test_real_estimator.py: the legs of the people no longer found become
  // point landmarks there; docs/perception.md, "World scenarios", items 5 and 6).
  double single_leg_surface_clearance_m = 0.0;
  // A candidate of a dropout run (LegCandidate::dropout_run) makes no person alone and no pair
  // with another of its run.
  bool separate_dropout_pieces = false;
  // A one-leg person's leg with an open edge (LegCandidate::open_edges) needs more points than
  // this; 0: no such rule.
  int single_leg_open_edge_max_points = 0;
};

// (range, bearing) covariance -> Cartesian covariance at that point, and back (first order).
Eigen::Matrix2d PolarToCartesianCovariance(double range_m, double bearing_rad,
                                           const Eigen::Matrix2d& polar);
Eigen::Matrix2d CartesianToPolarCovariance(double x_m, double y_m,
                                           const Eigen::Matrix2d& cartesian);

// PersonDetector::Detect's mark of a stub: a candidate that would be a one-leg person but has
// an open edge and at most single_leg_open_edge_max_points points.
constexpr uint8_t kStubLeg = 2;

class PersonDetector {
 public:
  // Fills `people` (cleared first) from `candidates` (every one a leg candidate; the caller
  // has applied its leg-likeness threshold). used[i] becomes 1 when candidate i is a leg of a
  // person, kStubLeg when it is a stub (no person, and the caller drops it from the point
  // features), 0 otherwise. People come in increasing bearing (ties: increasing leg_index[0]).
  // Non-finite candidates are skipped. Allocates only while its buffers grow.
  // `sight` (may be null: one-leg people centred on their leg) is the scan, for the one-leg
  // centre.
  void Detect(const std::vector<LegCandidate>& candidates, const PersonDetectionOptions& options,
              std::vector<PersonFeature>* people, std::vector<uint8_t>* used,
              const SightLines* sight = nullptr);

 private:
  struct Pair {
    double separation_m;
    uint32_t first;
    uint32_t second;
  };
  std::vector<Pair> pairs_;
  std::vector<Eigen::Vector2d> positions_;
};

}  // namespace slammtt
