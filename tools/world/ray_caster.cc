#include "tools/world/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slammtt {

namespace {

// A circle relative to the ray origin: centre offset and |offset|^2 - r^2 (<= 0: origin inside).
struct RelativeCircle {
  double dx = 0.0;
  double dy = 0.0;
  double c = 0.0;
  bool usable = false;
};

// A segment relative to the ray origin: first end p = (px, py) and direction d = end - start.
struct RelativeSegment {
  double px = 0.0;
  double py = 0.0;
  double dx = 0.0;
  double dy = 0.0;
};

// Nearest intersection of the unit-direction ray (ux, uy) with the relative circle, or a
// negative number for none. With the ray p(t) = t u, |p(t) - d|^2 = r^2 gives
// t^2 - 2 (u.d) t + (|d|^2 - r^2) = 0; the nearer root is b - sqrt(b^2 - c), b = u.d.
inline double Intersect(const RelativeCircle& circle, double ux, double uy) {
  if (circle.c <= 0.0) return 0.0;  // origin inside or on the circle
  const double b = ux * circle.dx + uy * circle.dy;
  if (b <= 0.0) return -1.0;  // centre behind the origin and origin outside: no hit ahead
  const double disc = b * b - circle.c;
  if (disc < 0.0) return -1.0;
  return b - std::sqrt(disc);
}

// Intersection of the ray t u with p + s d, s in [0, 1]: with cross(a, b) = a.x b.y - a.y b.x,
// t = cross(p, d) / cross(u, d) and s = cross(p, u) / cross(u, d); negative for none.
inline double Intersect(const RelativeSegment& segment, double ux, double uy) {
  const double denominator = ux * segment.dy - uy * segment.dx;
  if (denominator == 0.0) return -1.0;  // parallel
  const double t = (segment.px * segment.dy - segment.py * segment.dx) / denominator;
  const double s = (segment.px * uy - segment.py * ux) / denominator;
  if (t < 0.0 || s < 0.0 || s > 1.0) return -1.0;
  return t;
}

std::vector<RelativeCircle> Relative(double ox, double oy, const std::vector<Circle>& circles) {
  std::vector<RelativeCircle> out(circles.size());
  for (size_t i = 0; i < circles.size(); ++i) {
    const Circle& c = circles[i];
    out[i].usable = c.radius_m > 0.0;
    out[i].dx = c.x_m - ox;
    out[i].dy = c.y_m - oy;
    out[i].c = out[i].dx * out[i].dx + out[i].dy * out[i].dy - c.radius_m * c.radius_m;
  }
  return out;
}

std::vector<RelativeSegment> Relative(double ox, double oy,
                                      const std::vector<Segment>& segments) {
  std::vector<RelativeSegment> out(segments.size());
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    out[i] = RelativeSegment{s.x0_m - ox, s.y0_m - oy, s.x1_m - s.x0_m, s.y1_m - s.y0_m};
  }
  return out;
}

BeamHit Nearest(const std::vector<RelativeCircle>& circles,
                const std::vector<RelativeSegment>& segments, double ux, double uy) {
  BeamHit hit;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < circles.size(); ++i) {
    if (!circles[i].usable) continue;
    const double t = Intersect(circles[i], ux, uy);
    if (t >= 0.0 && t < best) {
      best = t;
      hit.circle = static_cast<int>(i);
    }
  }
  for (size_t i = 0; i < segments.size(); ++i) {
    const double t = Intersect(segments[i], ux, uy);
    if (t >= 0.0 && t < best) {
      best = t;
      hit.segment = static_cast<int>(i);
    }
  }
  if (hit.segment >= 0) {
    hit.circle = -1;
    const RelativeSegment& s = segments[static_cast<size_t>(hit.segment)];
    hit.incidence_cos = std::abs(ux * s.dy - uy * s.dx) / std::hypot(s.dx, s.dy);
  } else if (hit.circle >= 0 && best > 0.0) {
    // Normal at the hit point t u - d, of length r.
    const RelativeCircle& c = circles[static_cast<size_t>(hit.circle)];
    const double nx = best * ux - c.dx;
    const double ny = best * uy - c.dy;
    const double length = std::hypot(nx, ny);
    hit.incidence_cos = length > 0.0 ? std::min(1.0, std::abs(ux * nx + uy * ny) / length) : 1.0;
  }
  if (hit.hit()) hit.range_m = best;
  return hit;
}

}  // namespace

BeamHit CastRay(double origin_x_m, double origin_y_m, double world_angle_rad,
                const std::vector<Circle>& circles, const std::vector<Segment>& segments) {
  return Nearest(Relative(origin_x_m, origin_y_m, circles),
                 Relative(origin_x_m, origin_y_m, segments), std::cos(world_angle_rad),
                 std::sin(world_angle_rad));
}

std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles, double max_range_m) {
  return CastBeams(sensor, beam_angles_rad, circles, {}, max_range_m);
}

std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles,
                               const std::vector<Segment>& segments, double max_range_m) {
  const std::vector<RelativeCircle> relative = Relative(sensor.x_m, sensor.y_m, circles);
  const std::vector<RelativeSegment> relative_segments =
      Relative(sensor.x_m, sensor.y_m, segments);
  std::vector<BeamHit> hits(beam_angles_rad.size());
  for (size_t i = 0; i < beam_angles_rad.size(); ++i) {
    const double angle = sensor.heading_rad + beam_angles_rad[i];
    BeamHit hit = Nearest(relative, relative_segments, std::cos(angle), std::sin(angle));
    if (hit.hit() && hit.range_m > max_range_m) hit = BeamHit{};
    hits[i] = hit;
  }
  return hits;
}

namespace {

// Orientation of c relative to the line a -> b: > 0 left, < 0 right, 0 on it.
double Orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

bool SegmentsCross(const Segment& a, const Segment& b) {
  const double o1 = Orientation(a.x0_m, a.y0_m, a.x1_m, a.y1_m, b.x0_m, b.y0_m);
  const double o2 = Orientation(a.x0_m, a.y0_m, a.x1_m, a.y1_m, b.x1_m, b.y1_m);
  const double o3 = Orientation(b.x0_m, b.y0_m, b.x1_m, b.y1_m, a.x0_m, a.y0_m);
  const double o4 = Orientation(b.x0_m, b.y0_m, b.x1_m, b.y1_m, a.x1_m, a.y1_m);
  if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) &&
      ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))) {
    return true;
  }
  // Touching or collinear overlap: an end point lies on the other segment.
  return SquaredDistanceToSegment(b.x0_m, b.y0_m, a) == 0.0 ||
         SquaredDistanceToSegment(b.x1_m, b.y1_m, a) == 0.0 ||
         SquaredDistanceToSegment(a.x0_m, a.y0_m, b) == 0.0 ||
         SquaredDistanceToSegment(a.x1_m, a.y1_m, b) == 0.0;
}

}  // namespace

double SquaredDistanceToSegment(double px, double py, const Segment& s) {
  const double sx = s.x1_m - s.x0_m;
  const double sy = s.y1_m - s.y0_m;
  const double length2 = sx * sx + sy * sy;
  const double dx = px - s.x0_m;
  const double dy = py - s.y0_m;
  const double t = length2 > 0.0 ? std::clamp((dx * sx + dy * sy) / length2, 0.0, 1.0) : 0.0;
  const double ex = dx - t * sx;
  const double ey = dy - t * sy;
  return ex * ex + ey * ey;
}

bool CircleTouchesSegment(const Circle& circle, const Segment& segment) {
  return SquaredDistanceToSegment(circle.x_m, circle.y_m, segment) <=
         circle.radius_m * circle.radius_m;
}

bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore) {
  return SegmentBlocked(x0_m, y0_m, x1_m, y1_m, circles, ignore, ignore >= 0 ? 1 : 0, {});
}

bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore_first, int ignore_count,
                    const std::vector<Segment>& walls) {
  const Segment sight{x0_m, y0_m, x1_m, y1_m};
  for (size_t i = 0; i < circles.size(); ++i) {
    const int index = static_cast<int>(i);
    if ((index >= ignore_first && index < ignore_first + ignore_count) ||
        !(circles[i].radius_m > 0.0)) {
      continue;
    }
    if (CircleTouchesSegment(circles[i], sight)) return true;
  }
  for (const Segment& wall : walls) {
    if (SegmentsCross(sight, wall)) return true;
  }
  return false;
}

}  // namespace slammtt
