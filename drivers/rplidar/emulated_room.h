// The world the RPLIDAR emulator scans on its own: a rectangular room with a few pillars and a
// box, around a scanner fixed at the origin. Rays are cast by the synthetic world's ray caster
// (tools/world/ray_caster.h); a dark surface gives no return.
//
// Frame: the room frame has the scanner at the origin, x along the device's 0 direction and
// angles counter-clockwise; the device measures clockwise, so a sample at device angle a looks
// along room direction -a.
#pragma once

#include <optional>
#include <vector>

#include "drivers/rplidar/laser_scene.h"
#include "tools/world/ray_caster.h"

namespace slammtt {
namespace rplidar {

struct RoomSegment {
  double x0_m, y0_m, x1_m, y1_m;
  bool returns_light = true;  // false: a dark pane the laser gets no return from
};
struct RoomCircle {
  double x_m, y_m, radius_m;
};

class EmulatedRoom : public LaserScene {
 public:
  // The default room: 8 m x 6 m walls (x in [-3, 5], y in [-2.5, 3.5]) with a 1 m dark pane in
  // the wall at y = 3.5 (beams there get no return), three round pillars and a 1 m x 0.5 m box.
  static EmulatedRoom Default();
  EmulatedRoom(std::vector<RoomSegment> segments, std::vector<RoomCircle> circles);

  // Distance from the origin to the first surface along `direction_rad` (CCW from x), or
  // nullopt when the first surface gives no return or nothing is hit.
  std::optional<double> CastRay(double direction_rad) const;
  // The same for a device angle (clockwise degrees).
  std::optional<double> CastDeviceRay(double device_angle_deg) const;
  // LaserScene: the room does not change with time; a dark surface is no return at all.
  std::optional<SceneReturn> Cast(double device_angle_deg, int64_t time_us) const override;

 private:
  std::vector<Segment> segments_;
  std::vector<bool> segment_returns_light_;
  std::vector<Circle> circles_;
};

}  // namespace rplidar
}  // namespace slammtt
