// Ray casting of laser beams against circles and straight segments: the first surface each beam
// meets, so that an object behind another one is hidden exactly as far as geometry hides it
// (physical occlusion), and a wall hides what stands behind it.
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

// A straight surface in the world frame (a wall, one side of a desk), seen from both sides.
struct Segment {
  double x0_m = 0.0;
  double y0_m = 0.0;
  double x1_m = 0.0;
  double y1_m = 0.0;
};

// The first hit of one beam.
struct BeamHit {
  double range_m = 0.0;  // distance from the origin to the surface; meaningless without a hit
  int circle = -1;       // index into the circle list, -1 when the first hit is no circle
  int segment = -1;      // index into the segment list, -1 when the first hit is no segment
  // |cos| of the angle between the beam and the surface normal at the hit (1: head-on,
  // 0: grazing); 1 for a sensor inside a circle.
  double incidence_cos = 1.0;
  bool hit() const { return circle >= 0 || segment >= 0; }
};

// Intersects the ray origin + t * (cos a, sin a), t >= 0, with every circle and segment and
// returns the nearest intersection (at equal range a circle wins over a segment, a lower index
// over a higher one). A ray whose origin lies inside (or on) a circle hits that circle at range
// 0. Circles with radius <= 0 are never hit; a segment is hit from either side, also at its end
// points; a ray along a segment (parallel, collinear) does not hit it.
BeamHit CastRay(double origin_x_m, double origin_y_m, double world_angle_rad,
                const std::vector<Circle>& circles,
                const std::vector<Segment>& segments = {});

// Casts one beam per angle (sensor frame, CCW from the sensor's x axis) from `sensor` and
// returns the hits in the same order. Hits farther than max_range_m are reported as no hit
// (circle and segment -1): the sensor gets no return from them. Cost: beams x (circles +
// segments) intersection tests.
std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles, double max_range_m);
std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles,
                               const std::vector<Segment>& segments, double max_range_m);

// True when the straight segment from (x0, y0) to (x1, y1) crosses or touches any circle except
// the circles in [ignore_first, ignore_first + ignore_count) (ignore_first -1: none), or any of
// `walls`. Used for the line-of-sight rule of point features.
bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore);
bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore_first, int ignore_count,
                    const std::vector<Segment>& walls);

// Squared distance from the point (x, y) to the nearest point of the segment.
double SquaredDistanceToSegment(double x_m, double y_m, const Segment& segment);

// True when the circle touches or crosses the segment (the distance from its centre to the
// segment is at most its radius).
bool CircleTouchesSegment(const Circle& circle, const Segment& segment);

}  // namespace slammtt
