#include "tools/world/laser_model.h"

#include <algorithm>
#include <cmath>

#include "tools/world/portable_random.h"

namespace slammtt {

std::vector<double> LaserBeamAngles(const LaserSpec& laser) {
  const double resolution_rad = laser.resolution_deg * M_PI / 180.0;
  std::vector<double> angles;
  if (laser.fov_deg >= 360.0 - 1e-9) {
    const long n = std::lround(360.0 / laser.resolution_deg);
    angles.reserve(static_cast<size_t>(n));
    for (long i = 0; i < n; ++i) angles.push_back(-M_PI + static_cast<double>(i) * resolution_rad);
  } else {
    const long n = static_cast<long>(std::floor(laser.fov_deg / laser.resolution_deg + 1e-9)) + 1;
    const double first = -0.5 * laser.fov_deg * M_PI / 180.0;
    angles.reserve(static_cast<size_t>(n));
    for (long i = 0; i < n; ++i) angles.push_back(first + static_cast<double>(i) * resolution_rad);
  }
  return angles;
}

std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits, std::mt19937_64& rng) {
  std::vector<SimulatedBeam> beams(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    SimulatedBeam& beam = beams[i];
    beam.angle_rad = beam_angles_rad[i];
    const BeamHit& hit = hits[i];
    if (hit.circle < 0) continue;
    beam.object = hit.circle;
    beam.true_range_m = hit.range_m;
    if (hit.range_m < laser.min_range_m || hit.range_m > laser.max_range_m) continue;
    beam.valid = true;
    beam.range_m = std::clamp(hit.range_m + GaussianNoise(rng, laser.range_noise_m),
                              laser.min_range_m, laser.max_range_m);
  }
  return beams;
}

std::vector<int> CountBeamsPerObject(const std::vector<SimulatedBeam>& beams, int num_objects) {
  std::vector<int> counts(static_cast<size_t>(std::max(num_objects, 0)), 0);
  for (const SimulatedBeam& beam : beams) {
    if (beam.valid && beam.object >= 0 && beam.object < num_objects) {
      ++counts[static_cast<size_t>(beam.object)];
    }
  }
  return counts;
}

}  // namespace slammtt
