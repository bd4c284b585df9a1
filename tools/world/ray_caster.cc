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

BeamHit Nearest(const std::vector<RelativeCircle>& circles, double ux, double uy) {
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
  if (hit.circle >= 0) hit.range_m = best;
  return hit;
}

}  // namespace

BeamHit CastRay(double origin_x_m, double origin_y_m, double world_angle_rad,
                const std::vector<Circle>& circles) {
  return Nearest(Relative(origin_x_m, origin_y_m, circles), std::cos(world_angle_rad),
                 std::sin(world_angle_rad));
}

std::vector<BeamHit> CastBeams(const Pose2D& sensor, const std::vector<double>& beam_angles_rad,
                               const std::vector<Circle>& circles, double max_range_m) {
  const std::vector<RelativeCircle> relative = Relative(sensor.x_m, sensor.y_m, circles);
  std::vector<BeamHit> hits(beam_angles_rad.size());
  for (size_t i = 0; i < beam_angles_rad.size(); ++i) {
    const double angle = sensor.heading_rad + beam_angles_rad[i];
    BeamHit hit = Nearest(relative, std::cos(angle), std::sin(angle));
    if (hit.circle >= 0 && hit.range_m > max_range_m) hit = BeamHit{};
    hits[i] = hit;
  }
  return hits;
}

bool SegmentBlocked(double x0_m, double y0_m, double x1_m, double y1_m,
                    const std::vector<Circle>& circles, int ignore) {
  const double sx = x1_m - x0_m;
  const double sy = y1_m - y0_m;
  const double length2 = sx * sx + sy * sy;
  for (size_t i = 0; i < circles.size(); ++i) {
    if (static_cast<int>(i) == ignore || !(circles[i].radius_m > 0.0)) continue;
    const double dx = circles[i].x_m - x0_m;
    const double dy = circles[i].y_m - y0_m;
    const double t = length2 > 0.0 ? std::clamp((dx * sx + dy * sy) / length2, 0.0, 1.0) : 0.0;
    const double ex = dx - t * sx;
    const double ey = dy - t * sy;
    if (ex * ex + ey * ey <= circles[i].radius_m * circles[i].radius_m) return true;
  }
  return false;
}

}  // namespace slammtt
