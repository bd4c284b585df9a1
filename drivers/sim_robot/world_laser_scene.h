// The emulated RPLIDAR's view of a shared EmulatedRobotWorld (tools/world): a device angle at a
// moment of the device's clock becomes a beam of the world's laser, cast from the robot's true
// pose at that moment. The world is shared with the thread that moves it; every cast takes the
// world's lock.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>

#include "drivers/rplidar/laser_scene.h"
#include "tools/world/emulated_robot_world.h"

namespace slammtt {

class WorldLaserScene : public rplidar::LaserScene {
 public:
  // World time = device time - `world_start_us` (both microseconds of the same monotonic
  // clock). `world` and `mutex` outlive the scene.
  WorldLaserScene(const EmulatedRobotWorld* world, std::mutex* mutex, int64_t world_start_us);

  // The A2 measures clockwise from its 0 mark, the world's sensor frame counter-clockwise
  // (rplidar_beams.h with angle_offset_deg 0): sensor angle = -device angle.
  std::optional<rplidar::SceneReturn> Cast(double device_angle_deg,
                                           int64_t time_us) const override;

 private:
  const EmulatedRobotWorld* world_;
  std::mutex* mutex_;
  int64_t world_start_us_;
};

}  // namespace slammtt
