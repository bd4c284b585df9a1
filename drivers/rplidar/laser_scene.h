// What an emulated RPLIDAR sees: the first surface along one of its beams at one moment. The
// device model (rplidar_device_model.h) asks the scene for every sample it measures; a fixed
// room (emulated_room.h) and a simulated world with a moving robot (drivers/sim_robot) are
// scenes. Pure interface: no I/O, no clock (the time is the device model's).
#pragma once

#include <cstdint>
#include <optional>

namespace slammtt {
namespace rplidar {

// The first surface a beam meets.
struct SceneReturn {
  double range_m = 0.0;  // from the scanner's centre
  // Probability that this surface gives no return (a glass pane, a grazing angle): the device
  // model draws it per sample from its seeded hash, so the bytes stay reproducible.
  double dropout_probability = 0.0;
};

class LaserScene {
 public:
  virtual ~LaserScene() = default;
  // The first surface along device angle `device_angle_deg` (clockwise degrees from the
  // device's 0 mark, as the A2 measures) at `time_us` (the device model's time base: the moment
  // the sample is measured), or nullopt when the beam meets nothing. Called from the thread
  // that runs the device model; a scene shared with another thread locks for itself.
  virtual std::optional<SceneReturn> Cast(double device_angle_deg, int64_t time_us) const = 0;
};

}  // namespace rplidar
}  // namespace slammtt
