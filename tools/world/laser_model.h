// The synthetic laser scanner: beam geometry of a LaserSpec and the measurement of one scan from
// ray-cast hits (per-beam Gaussian range noise, minimum and maximum range). Invalid beams stay in
// the scan (valid = false), as the RPLIDAR driver does.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "tools/world/ray_caster.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Beam directions in the sensor frame (see LaserSpec), in scan order (CCW).
std::vector<double> LaserBeamAngles(const LaserSpec& laser);

// One measured beam.
struct SimulatedBeam {
  double angle_rad = 0.0;     // sensor frame
  double range_m = 0.0;       // measured (true + noise, clamped to [min, max]); 0 when invalid
  double true_range_m = 0.0;  // noise-free range of the hit; 0 without a hit
  bool valid = false;         // a surface within [min_range, max_range]
  int object = -1;            // index of the hit object in the world's circle list, -1 for none
};

// Measures one scan from the ray-cast hits of LaserBeamAngles(laser): a beam is valid when its
// first hit lies within [min_range_m, max_range_m]; its range is the true range plus
// N(0, range_noise_m^2), clamped to that interval. A hit nearer than min_range_m (e.g. an
// object touching the sensor) gives an invalid beam that still names the object it hit.
// Draws one normal number per valid beam from `rng`.
std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits, std::mt19937_64& rng);

// Number of valid beams whose first hit is each object (size num_objects): the ground truth's
// beams_on_object.
std::vector<int> CountBeamsPerObject(const std::vector<SimulatedBeam>& beams, int num_objects);

}  // namespace slammtt
