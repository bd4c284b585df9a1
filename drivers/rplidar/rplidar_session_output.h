// What the RPLIDAR device session (rplidar_session.h) reports, as plain structs: a scan per
// revolution and the state of the driver and device. The program's adapter turns them into
// LASER_SCAN and LIDAR_STATUS (rplidar_messages.h, whose fields these are, one for one); a test
// records them as they are.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "drivers/rplidar/rplidar_beams.h"
#include "drivers/rplidar/rplidar_driver_options.h"
#include "drivers/rplidar/rplidar_protocol.h"

namespace slammtt {
namespace rplidar {

// One revolution in the sensor frame (rplidar_beams.h: x forward, y left, angles CCW).
struct LaserScan {
  int64_t utime = 0;             // host time the first sample's bytes arrived [us since epoch]
  int64_t sequence = 0;          // 0, 1, 2, ... per session object
  int64_t scan_duration_us = 0;  // from the first sample's arrival to the last one's
  double range_min_m = 0.0;      // the configured valid range (beams outside it: valid false)
  double range_max_m = 0.0;
  Beams beams;                   // one beam per sample, in the device's order
};

// Where the session is: "connecting" until the first link opens, "scanning", "reconnecting"
// after a link error, "health_error" while a device error refuses the scan, "stopped" at the end.
enum class LidarState { kConnecting, kScanning, kReconnecting, kHealthError, kStopped };
const char* LidarStateName(LidarState state);

struct LidarStatus {
  int64_t utime = 0;  // host time of the report [us since epoch]
  bool connected = false;
  LidarState state = LidarState::kConnecting;
  std::string endpoint;  // the configured port, then the open link's ByteStream::Describe()
  // GET_INFO of the device last connected; 0 and "" before.
  int model = 0;
  int firmware_major = 0;
  int firmware_minor = 0;
  int hardware = 0;
  std::string serial_number;              // 32 hexadecimal digits
  std::optional<DeviceHealth> health;     // GET_HEALTH's last answer; none before the first
  ScanMode scan_mode = ScanMode::kExpress;  // the configured mode, then the one in use
  double scan_rate_hz = 0.0;              // revolutions per second, recent; 0 unless scanning
  int64_t scans_published = 0;
  int64_t nodes_decoded = 0;              // samples, both decoders
  int64_t resyncs = 0;                    // times a decoder discarded bytes to find a sample
  int64_t checksum_errors = 0;            // express capsules with a bad checksum
  int64_t reconnects = 0;
  std::string last_error;                 // "" until something went wrong
};

// Where the session sends what it measured. Called on the session's thread; an exception
// thrown here ends RplidarSession::Run (after the scan and the motor were stopped).
class RplidarSessionOutput {
 public:
  virtual ~RplidarSessionOutput() = default;
  virtual void OnLaserScan(const LaserScan& scan) = 0;
  virtual void OnLidarStatus(const LidarStatus& status) = 0;
};

}  // namespace rplidar
}  // namespace slammtt
