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
// Covariance, in Cartesian coordinates and then in range/bearing of the centre (first-order):
//   two legs: (P1 + P2) / 4 + pair_centre_sigma_m^2 I (the body's centre is not exactly the
//             midpoint of the legs);
//   one leg:  P1 + single_leg_offset_sigma_m^2 I (the centre is anywhere within about half a
//             stride of the leg).
// Confidence: sqrt(l1 l2) for a pair, 0.5 l1 for a single leg (l: leg-likeness).
#pragma once

#include <Eigen/Core>

#include <cstdint>
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
  int32_t feature_index = -1;  // copied into PersonFeature::leg_index
};

struct PersonDetectionOptions {
  double min_leg_separation_m = 0.1;
  double max_leg_separation_m = 0.7;
  double single_leg_threshold = 0.65;
  double pair_centre_sigma_m = 0.05;
  double single_leg_offset_sigma_m = 0.15;
};

// (range, bearing) covariance -> Cartesian covariance at that point, and back (first order).
Eigen::Matrix2d PolarToCartesianCovariance(double range_m, double bearing_rad,
                                           const Eigen::Matrix2d& polar);
Eigen::Matrix2d CartesianToPolarCovariance(double x_m, double y_m,
                                           const Eigen::Matrix2d& cartesian);

class PersonDetector {
 public:
  // Fills `people` (cleared first) from `candidates` (every one a leg candidate; the caller
  // has applied its leg-likeness threshold). used[i] becomes 1 when candidate i is a leg of a
  // person. People come in increasing bearing (ties: increasing leg_index[0]).
  // Non-finite candidates are skipped. Allocates only while its buffers grow.
  void Detect(const std::vector<LegCandidate>& candidates, const PersonDetectionOptions& options,
              std::vector<PersonFeature>* people, std::vector<uint8_t>* used);

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
