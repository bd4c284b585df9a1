#include "drivers/sim_robot/world_laser_scene.h"

#include <cmath>

namespace slammtt {

WorldLaserScene::WorldLaserScene(const EmulatedRobotWorld* world, std::mutex* mutex,
                                 int64_t world_start_us)
    : world_(world), mutex_(mutex), world_start_us_(world_start_us) {}

std::optional<rplidar::SceneReturn> WorldLaserScene::Cast(double device_angle_deg,
                                                          int64_t time_us) const {
  std::optional<BeamSurface> surface;
  {
    std::lock_guard<std::mutex> lock(*mutex_);
    surface = world_->CastBeam(-device_angle_deg * M_PI / 180.0, time_us - world_start_us_);
  }
  if (!surface) return std::nullopt;
  return rplidar::SceneReturn{surface->range_m, surface->dropout_probability};
}

}  // namespace slammtt
