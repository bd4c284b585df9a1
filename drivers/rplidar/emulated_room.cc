#include "drivers/rplidar/emulated_room.h"

#include <cmath>
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

EmulatedRoom::EmulatedRoom(std::vector<RoomSegment> segments, std::vector<RoomCircle> circles) {
  for (const RoomSegment& s : segments) {
    segments_.push_back(Segment{s.x0_m, s.y0_m, s.x1_m, s.y1_m});
    segment_returns_light_.push_back(s.returns_light);
  }
  for (const RoomCircle& c : circles) circles_.push_back(Circle{c.x_m, c.y_m, c.radius_m});
}

std::optional<double> EmulatedRoom::CastRay(double direction_rad) const {
  const BeamHit hit = slammtt::CastRay(0.0, 0.0, direction_rad, circles_, segments_);
  if (!hit.hit()) return std::nullopt;
  if (hit.segment >= 0 && !segment_returns_light_[static_cast<size_t>(hit.segment)]) {
    return std::nullopt;
  }
  return hit.range_m;
}

std::optional<double> EmulatedRoom::CastDeviceRay(double device_angle_deg) const {
  return CastRay(-device_angle_deg * kPi / 180.0);
}

std::optional<SceneReturn> EmulatedRoom::Cast(double device_angle_deg, int64_t) const {
  const std::optional<double> range_m = CastDeviceRay(device_angle_deg);
  if (!range_m) return std::nullopt;
  return SceneReturn{*range_m, 0.0};
}

}  // namespace rplidar
}  // namespace slammtt
