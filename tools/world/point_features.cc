#include "tools/world/point_features.h"

#include <algorithm>
#include <cmath>

#include "tools/world/portable_random.h"

namespace slammtt {

std::vector<PointFeature> EmitPointFeatures(const Pose2D& sensor,
                                            const std::vector<FeatureTarget>& targets,
                                            const std::vector<Circle>& circles,
                                            const std::vector<Segment>& walls,
                                            const LaserSpec& laser, const FeatureSpec& spec,
                                            std::mt19937_64& rng, std::vector<bool>* visible) {
  const double half_fov_rad = 0.5 * laser.fov_deg * M_PI / 180.0;
  const bool full_circle = laser.fov_deg >= 360.0 - 1e-9;
  const double bearing_sigma_rad = spec.bearing_noise_deg * M_PI / 180.0;
  std::vector<PointFeature> features;
  visible->assign(targets.size(), false);
  for (size_t i = 0; i < targets.size(); ++i) {
    const FeatureTarget& c = targets[i];
    const double dx = c.x_m - sensor.x_m;
    const double dy = c.y_m - sensor.y_m;
    const double range = std::hypot(dx, dy);
    const double bearing = WrapAngle(std::atan2(dy, dx) - sensor.heading_rad);
    if (!full_circle && std::abs(bearing) > half_fov_rad) continue;           // rule 1
    if (range < laser.min_range_m || range > laser.max_range_m) continue;     // rule 2
    if (c.beams_on_target <= 0 && SegmentBlocked(sensor.x_m, sensor.y_m, c.x_m, c.y_m, circles,
                                                 c.first_circle, c.num_circles, walls)) {
      continue;                                                               // rule 3
    }
    if (spec.detection_probability < 1.0 && !(UniformUnit(rng) < spec.detection_probability)) {
      continue;                                                               // rule 4
    }
    PointFeature feature;
    feature.object = static_cast<int>(i);
    feature.range_m = std::max(0.0, range + GaussianNoise(rng, spec.range_noise_m));
    feature.bearing_rad = WrapAngle(bearing + GaussianNoise(rng, bearing_sigma_rad));
    feature.width_m = c.width_m;
    feature.range_var_m2 = spec.range_noise_m * spec.range_noise_m;
    feature.bearing_var_rad2 = bearing_sigma_rad * bearing_sigma_rad;
    features.push_back(feature);
    (*visible)[i] = true;
  }
  std::stable_sort(features.begin(), features.end(),
                   [](const PointFeature& a, const PointFeature& b) {
                     return a.bearing_rad < b.bearing_rad;
                   });
  return features;
}

std::vector<PointFeature> EmitPointFeatures(const Pose2D& sensor,
                                            const std::vector<Circle>& circles,
                                            const std::vector<int>& beams_on_object,
                                            const LaserSpec& laser, const FeatureSpec& spec,
                                            std::mt19937_64& rng, std::vector<bool>* visible) {
  std::vector<FeatureTarget> targets(circles.size());
  for (size_t i = 0; i < circles.size(); ++i) {
    targets[i] = FeatureTarget{circles[i].x_m, circles[i].y_m, 2.0 * circles[i].radius_m,
                               i < beams_on_object.size() ? beams_on_object[i] : 0,
                               static_cast<int>(i), 1};
  }
  return EmitPointFeatures(sensor, targets, circles, {}, laser, spec, rng, visible);
}

}  // namespace slammtt
