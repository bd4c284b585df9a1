// The synthetic laser scanner: beam geometry of a LaserSpec and the measurement of one scan from
// ray-cast hits (per-beam Gaussian range noise, minimum and maximum range, and the artefacts of
// LaserArtefactSpec). Invalid beams stay in the scan (valid = false), as the RPLIDAR driver
// does.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "tools/world/ray_caster.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Beam directions in the sensor frame (see LaserSpec), in scan order (CCW): the even layout.
std::vector<double> LaserBeamAngles(const LaserSpec& laser);

// The beam directions of successive scans. Even layout (artefacts.sample_rate_hz 0): the same
// LaserBeamAngles() every scan, no draws. Sampled (RPLIDAR-like, 360 degrees only): the device
// measures at sample_rate_hz while its head turns clockwise at rate_hz * (1 + rotation_jitter *
// n) in this revolution (n ~ N(0,1) drawn once per scan, the factor clamped to [0.5, 1.5]);
// sample k of a revolution is at device angle theta_0 + k * step plus N(0, angle_jitter_deg^2),
// step = 360 * rate / sample_rate degrees, up to the wrap past 360 degrees; the next revolution
// starts where this one's next sample falls after the wrap (theta_0 in [0, step)), so the first
// angle and the number of beams change from scan to scan, as with the real A2
// (docs/rplidar.md: revolutions are cut where the angle wraps). Beams are listed in the order
// measured, sensor angle = wrap(-device angle) (rplidar_beams.h with angle_offset_deg 0): CW,
// decreasing from 0.
class BeamAngleSequence {
 public:
  explicit BeamAngleSequence(const LaserSpec& laser);
  std::vector<double> Next(std::mt19937_64& rng);
  bool sampled() const { return sampled_; }

 private:
  LaserSpec laser_;
  bool sampled_ = false;
  std::vector<double> even_;
  double next_device_deg_ = 0.0;
};

// One measured beam.
struct SimulatedBeam {
  double angle_rad = 0.0;     // sensor frame
  double range_m = 0.0;       // measured (true + noise, clamped to [min, max]); 0 when invalid
  double true_range_m = 0.0;  // noise-free range of the beam's first surface; 0 without a hit
  bool valid = false;         // a return within [min_range, max_range]
  // The beam's first surface, whatever the sensor reported: MeasureScan sets the ray caster's
  // circle index, WorldSimulator turns it into the index of the object in truth.objects.
  int object = -1;
  int segment = -1;           // index of the hit static segment, -1 for none
  bool mixed_pixel = false;   // the range lies between two surfaces of a depth edge
  bool dropout = false;       // a surface was hit but gave no return (surface, grazing angle)
};

// What the artefacts need besides the beams' hits: the hits of the two edges of each beam's
// footprint (rays at -+ beam_divergence_deg / 2; empty when mixed pixels are off) and the
// dropout probability of every circle and segment (empty: none).
struct ArtefactInputs {
  std::vector<BeamHit> lower_edge_hits;
  std::vector<BeamHit> upper_edge_hits;
  std::vector<double> circle_dropout_probability;
  std::vector<double> segment_dropout_probability;
};

// Measures one scan from the ray-cast hits of `beam_angles_rad`. A beam with a hit is, in order:
//   1. invalid when its range lies outside [min_range_m, max_range_m];
//   2. a dropout (no return) with the dropout probability of its surface (one uniform draw from
//      artefact_rng when that probability is > 0), or when its incidence angle exceeds
//      grazing_dropout_deg;
//   3. a mixed pixel when its footprint's edges hit two different surfaces whose ranges differ
//      by more than mixed_pixel_min_gap_m, with mixed_pixel_probability (one uniform draw from
//      artefact_rng when so): its noise-free range becomes uniform between the two ranges
//      (a second draw);
//   4. valid: range = that range + N(0, sigma^2), sigma = range_noise_m + range_noise_per_m *
//      range, clamped to [min, max] (one normal draw from `rng` per valid beam).
// A hit nearer than min_range_m (e.g. an object touching the sensor) gives an invalid beam that
// still names the object it hit. With every artefact off this draws exactly what the laser drew
// before artefacts existed (one normal number per valid beam), so old scenarios keep their bytes.
std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits, std::mt19937_64& rng);
std::vector<SimulatedBeam> MeasureScan(const LaserSpec& laser,
                                       const std::vector<double>& beam_angles_rad,
                                       const std::vector<BeamHit>& hits,
                                       const ArtefactInputs& artefacts, std::mt19937_64& rng,
                                       std::mt19937_64& artefact_rng);

// True when the scan needs the footprint edges (mixed pixels on).
bool NeedsFootprintEdges(const LaserSpec& laser);

// Number of valid beams whose first hit is each object (size num_objects): the ground truth's
// beams_on_object.
std::vector<int> CountBeamsPerObject(const std::vector<SimulatedBeam>& beams, int num_objects);

}  // namespace slammtt
