// Ray casting of laser beams against circles: the first surface each beam meets, so that an
// object behind another one is hidden exactly as far as geometry hides it (physical occlusion).
#pragma once

#include <cstdint>
#include <vector>

#include "tools/world/planar_pose.h"

namespace slammtt {

// A circular object in the world frame.
struct Circle {
  double x_m = 0.0;
  double y_m = 0.0;
  double radius_m = 0.0;
};

// The first hit of one beam.
struct BeamHit {
  double range_m = 0.0;  // distance from the origin to the surface; meaningless without a hit
  int circle = -1;       // index into the circle list, -1 when the beam hits nothing
};

// Intersects the ray origin + t * (cos a, sin a), t >= 0, with every circle and returns the
// nearest intersection. A ray whose origin lies inside (or on) a circle hits that circle at
// range 0. Circles with radius <= 0 are never hit.
BeamHit CastRay(double origin_x_m, double origin_y_m, double world_angle_rad,
                const std::vector<Circle>& circles);

// Casts one beam per angle (sensor frame, CCW from the sensor's x axis) from `sensor` and
// returns the hits in the same order. Hits farther than max_range_m are reported as no hit
// (circle -1): the sensor gets no return from them. Cost: beams x circles intersection tests.
std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles, double max_range_m);

// True when the straight segment from (x0, y0) to (x1, y1) crosses or touches any circle except
// circle `ignore` (-1: none). Used for the line-of-sight rule of point features.
bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore);

}  // namespace slammtt
