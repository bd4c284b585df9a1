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

BeamAngleSequence::BeamAngleSequence(const LaserSpec& laser)
    : laser_(laser),
      sampled_(laser.artefacts.sample_rate_hz > 0.0),
      even_(LaserBeamAngles(laser)) {}

std::vector<double> BeamAngleSequence::Next(std::mt19937_64& rng) {
  if (!sampled_) return even_;
  const LaserArtefactSpec& a = laser_.artefacts;
  const double speed_factor =
      std::clamp(1.0 + GaussianNoise(rng, a.rotation_jitter), 0.5, 1.5);
  const double step_deg = 360.0 * laser_.rate_hz * speed_factor / a.sample_rate_hz;
  std::vector<double> angles;
  angles.reserve(static_cast<size_t>(360.0 / step_deg) + 2);
  double device_deg = next_device_deg_;
  for (; device_deg < 360.0; device_deg += step_deg) {
    const double measured_deg = device_deg + GaussianNoise(rng, a.angle_jitter_deg);
    angles.push_back(WrapAngle(-measured_deg * M_PI / 180.0));
  }
  next_device_deg_ = device_deg - 360.0;
  return angles;
}

bool NeedsFootprintEdges(const LaserSpec& laser) {
  return laser.artefacts.mixed_pixel_probability > 0.0;
}

namespace {

double DropoutProbability(const BeamHit& hit, const ArtefactInputs& artefacts) {
  if (hit.circle >= 0 &&
      static_cast<size_t>(hit.circle) < artefacts.circle_dropout_probability.size()) {
    return artefacts.circle_dropout_probability[static_cast<size_t>(hit.circle)];
  }
  if (hit.segment >= 0 &&
      static_cast<size_t>(hit.segment) < artefacts.segment_dropout_probability.size()) {
    return artefacts.segment_dropout_probability[static_cast<size_t>(hit.segment)];
  }
  return 0.0;
}

bool SameSurface(const BeamHit& a, const BeamHit& b) {
  return a.circle == b.circle && a.segment == b.segment;
}

}  // namespace

std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits, std::mt19937_64& rng) {
  std::mt19937_64 unused;
  return MeasureScan(laser, beam_angles_rad, hits, ArtefactInputs{}, rng, unused);
}

std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits,
                                       const ArtefactInputs& artefacts, std::mt19937_64& rng,
                                       std::mt19937_64& artefact_rng) {
  const LaserArtefactSpec& a = laser.artefacts;
  const bool grazing = a.grazing_dropout_deg < 90.0;
  const double grazing_cos = std::cos(a.grazing_dropout_deg * M_PI / 180.0);
  const bool edges = a.mixed_pixel_probability > 0.0 &&
                     artefacts.lower_edge_hits.size() == hits.size() &&
                     artefacts.upper_edge_hits.size() == hits.size();
  std::vector<SimulatedBeam> beams(hits.size());
  for (size_t i = 0; i < hits.size(); ++i) {
    SimulatedBeam& beam = beams[i];
    beam.angle_rad = beam_angles_rad[i];
    const BeamHit& hit = hits[i];
    if (!hit.hit()) continue;
    beam.object = hit.circle;
    beam.segment = hit.segment;
    beam.true_range_m = hit.range_m;
    if (hit.range_m < laser.min_range_m || hit.range_m > laser.max_range_m) continue;
    const double dropout = DropoutProbability(hit, artefacts);
    if (dropout > 0.0 && UniformUnit(artefact_rng) < dropout) {
      beam.dropout = true;
      continue;
    }
    if (grazing && hit.incidence_cos < grazing_cos) {
      beam.dropout = true;
      continue;
    }
    double range = hit.range_m;
    if (edges) {
      const BeamHit& low = artefacts.lower_edge_hits[i];
      const BeamHit& high = artefacts.upper_edge_hits[i];
      if (low.hit() && high.hit() && !SameSurface(low, high) &&
          std::abs(low.range_m - high.range_m) > a.mixed_pixel_min_gap_m &&
          UniformUnit(artefact_rng) < a.mixed_pixel_probability) {
        range = UniformBetween(artefact_rng, std::min(low.range_m, high.range_m),
                               std::max(low.range_m, high.range_m));
        beam.mixed_pixel = true;
      }
    }
    beam.valid = true;
    const double sigma = laser.range_noise_m + a.range_noise_per_m * range;
    beam.range_m =
        std::clamp(range + GaussianNoise(rng, sigma), laser.min_range_m, laser.max_range_m);
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
