// Point features straight from the objects, as in the paper's own simulation (section 5.1):
// range and bearing of each visible object's centre from the sensor, with Gaussian noise
// (paper: 0.2 m and 2 degrees), the covariance of eq. 14.
//
// Visibility rule (a feature is emitted for an object when all hold):
//   1. the bearing of its centre lies inside the laser's field of view (always for 360 degrees);
//   2. the range of its centre lies within [min_range_m, max_range_m];
//   3. it is not fully occluded: at least one beam of the laser geometry has it as first hit,
//      or the straight line from the sensor to its centre crosses no other object (this keeps a
//      small object between two beams visible when nothing hides it);
//   4. a draw against detection_probability succeeds (no draw when it is 1).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "tools/world/planar_pose.h"
#include "tools/world/ray_caster.h"
#include "tools/world/scenario.h"

namespace slammtt {

struct PointFeature {
  int object = -1;          // index of the target (truth, not published)
  double range_m = 0.0;     // noisy range of the centre from the sensor
  double bearing_rad = 0.0; // noisy bearing, sensor frame, wrapped to (-pi, pi]
  double width_m = 0.0;     // the object's diameter
  double range_var_m2 = 0.0;
  double bearing_var_rad2 = 0.0;
};

// Something that gives one point feature: a compact object (one circle) or a person (its centre;
// its legs are its surface). The line-of-sight rule ignores the target's own circles
// [first_circle, first_circle + num_circles).
struct FeatureTarget {
  double x_m = 0.0;
  double y_m = 0.0;
  double width_m = 0.0;     // published width
  int beams_on_target = 0;  // valid beams whose first hit is the target (rule 3)
  int first_circle = -1;
  int num_circles = 0;
};

// The features of one scan from `targets`, occluded by `circles` and `walls` (rule 3), sorted by
// increasing noisy bearing; `visible` is resized to targets.size(). Same draws as below.
std::vector<PointFeature> EmitPointFeatures(const Pose2D& sensor,
                                            const std::vector<FeatureTarget>& targets,
                                            const std::vector<Circle>& circles,
                                            const std::vector<Segment>& walls,
                                            const LaserSpec& laser, const FeatureSpec& spec,
                                            std::mt19937_64& rng, std::vector<bool>* visible);

// Every circle a target of its own diameter: the features of one scan, sorted by increasing noisy
// bearing (as a scan would list them; the order says nothing about identity). `beams_on_object`
// comes from CountBeamsPerObject() for the same scan. `visible` (resized to circles.size()) tells
// for every object whether rules 1-3 held and the detection draw succeeded. Draws: for each object
// passing rules 1-3, one uniform number when detection_probability < 1, then one normal number each
// for range and bearing noise when non-zero.
std::vector<PointFeature> EmitPointFeatures(const Pose2D& sensor,
                                            const std::vector<Circle>& circles,
                                            const std::vector<int>& beams_on_object,
                                            const LaserSpec& laser, const FeatureSpec& spec,
                                            std::mt19937_64& rng, std::vector<bool>* visible);

}  // namespace slammtt
