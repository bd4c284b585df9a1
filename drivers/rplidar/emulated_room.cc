#include "drivers/rplidar/emulated_room.h"

#include <cmath>
#include <limits>
#include <utility>

namespace slammtt {
namespace rplidar {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

EmulatedRoom EmulatedRoom::Default() {
  std::vector<RoomSegment> segments = {
      {-3.0, -2.5, 5.0, -2.5, true},   // south wall
      {5.0, -2.5, 5.0, 3.5, true},     // east wall
      {5.0, 3.5, 1.5, 3.5, true},      // north wall, east part
      {1.5, 3.5, 0.5, 3.5, false},     // dark pane: no return
      {0.5, 3.5, -3.0, 3.5, true},     // north wall, west part
      {-3.0, 3.5, -3.0, -2.5, true},   // west wall
      // a 1 m x 0.5 m box
      {1.0, -1.8, 2.0, -1.8, true},
      {2.0, -1.8, 2.0, -1.3, true},
      {2.0, -1.3, 1.0, -1.3, true},
      {1.0, -1.3, 1.0, -1.8, true},
  };
  std::vector<RoomCircle> circles = {{2.0, 1.0, 0.3}, {-1.5, -1.0, 0.2}, {3.5, 2.0, 0.4}};
  return EmulatedRoom(std::move(segments), std::move(circles));
}

EmulatedRoom::EmulatedRoom(std::vector<RoomSegment> segments, std::vector<RoomCircle> circles)
    : segments_(std::move(segments)), circles_(std::move(circles)) {}

std::optional<double> EmulatedRoom::CastRay(double direction_rad) const {
  const double dx = std::cos(direction_rad);
  const double dy = std::sin(direction_rad);
  double best = std::numeric_limits<double>::infinity();
  bool best_returns = false;
  for (const RoomSegment& s : segments_) {
    // Solve t * d = p0 + u * (p1 - p0), t > 0, u in [0, 1].
    const double ex = s.x1_m - s.x0_m;
    const double ey = s.y1_m - s.y0_m;
    const double denominator = dx * ey - dy * ex;
    if (std::fabs(denominator) < 1e-12) continue;
    const double t = (s.x0_m * ey - s.y0_m * ex) / denominator;
    const double u = (s.x0_m * dy - s.y0_m * dx) / denominator;
    if (t > 1e-9 && u >= 0.0 && u <= 1.0 && t < best) {
      best = t;
      best_returns = s.returns_light;
    }
  }
  for (const RoomCircle& c : circles_) {
    // |t d - c|^2 = r^2  ->  t^2 - 2 t (d.c) + |c|^2 - r^2 = 0
    const double b = dx * c.x_m + dy * c.y_m;
    const double discriminant = b * b - (c.x_m * c.x_m + c.y_m * c.y_m - c.radius_m * c.radius_m);
    if (discriminant < 0.0) continue;
    const double t = b - std::sqrt(discriminant);
    if (t > 1e-9 && t < best) {
      best = t;
      best_returns = true;
    }
  }
  if (!std::isfinite(best) || !best_returns) return std::nullopt;
  return best;
}

std::optional<double> EmulatedRoom::CastDeviceRay(double device_angle_deg) const {
  return CastRay(-device_angle_deg * kPi / 180.0);
}

}  // namespace rplidar
}  // namespace slammtt
