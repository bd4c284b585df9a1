#include "drivers/rplidar/rplidar_session_output.h"

namespace slammtt {
namespace rplidar {

const char* LidarStateName(LidarState state) {
  switch (state) {
    case LidarState::kConnecting: return "connecting";
    case LidarState::kScanning: return "scanning";
    case LidarState::kReconnecting: return "reconnecting";
    case LidarState::kHealthError: return "health_error";
    case LidarState::kStopped: return "stopped";
  }
  return "unknown";
}

}  // namespace rplidar
}  // namespace slammtt
