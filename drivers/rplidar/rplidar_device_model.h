// The device side of an RPLIDAR A2, as a pure state machine: host bytes and the time in,
// the bytes the device transmits out. The emulator program and the tests drive it through a
// transport (pty or TCP, rplidar_emulator_server.h); nothing here does I/O or reads a clock.
//
// What it answers (protocol document; sl_lidar_cmd.h):
//   STOP          stops the scan, no reply
//   RESET         stops, reboots for reset_boot_us (ignores requests), then prints a text
//                 banner; a health problem clears unless health_persists_after_reset
//   SCAN          descriptor A5 5A 05 00 00 40 81, then 5-byte nodes once the motor is at speed
//   FORCE_SCAN    the same, as soon as the motor turns
//   EXPRESS_SCAN  working mode 0 only: descriptor A5 5A 54 00 00 40 82, then 84-byte capsules
//   GET_INFO      model, firmware, hardware, serial number
//   GET_HEALTH    status and error code
//   GET_SAMPLERATE  standard and express time per sample
//   GET_ACC_BOARD_FLAG  bit 0 = accessory_board (motor takes SET_MOTOR_PWM)
//   SET_MOTOR_PWM motor speed command, only with accessory_board
// Any other request (GET_LIDAR_CONF, unknown commands, express modes other than 0) gets no
// reply, as older firmware does; a request other than SET_MOTOR_PWM stops a running scan.
//
// The motor turns when: accessory_board and PWM > 0; otherwise when the host's DTR line is
// deasserted (A1/A2 through the USB adapter: sl_lidar_driver.cpp setMotorSpeed clears DTR to
// start the motor); when the DTR line cannot be observed (TCP), it always turns.
//
// Samples: sample k of a scan is taken at device angle start + k * sample_time * rotation_hz *
// 360 degrees (clockwise) at time epoch + k * sample_time (epoch: when the data stream started);
// its distance is what `scene` has along that angle at that time plus Gaussian noise (and no
// return with the surface's dropout probability), drawn from a hash of (seed, k) so that the
// bytes of a scan do not depend on how the transport paced them (as long as it polls within
// the backlog the device keeps: one revolution; beyond, samples are skipped and the next
// express capsule carries the S bit, so the host restarts its interpolation instead of
// bridging the gap). Express capsules carry per-sample angle corrections dtheta drawn the same
// way, and the distance of each sample is measured at the corrected angle, so a correct
// decoder recovers exactly the angles that were ray-cast.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "drivers/rplidar/emulated_room.h"
#include "drivers/rplidar/laser_scene.h"
#include "drivers/rplidar/rplidar_protocol.h"
#include "drivers/rplidar/rplidar_scan_decoder.h"

namespace slammtt {
namespace rplidar {

struct RplidarDeviceOptions {
  DeviceInfo info = DefaultInfo();
  DeviceHealth health;                       // what GET_HEALTH reports after power-up
  bool health_persists_after_reset = false;  // false: RESET clears a warning or error
  bool accessory_board = false;
  double rotation_hz = 10.0;
  uint16_t standard_sample_us = 500;  // A2: 2000 samples/s in standard mode
  uint16_t express_sample_us = 250;   // A2: 4000 samples/s in legacy express mode
  int64_t spin_up_us = 300000;        // motor start to stable rotation
  int64_t reset_boot_us = 200000;     // RESET to ready
  double range_noise_m = 0.005;       // standard deviation of the distance noise
  double max_range_m = 12.0;          // farther surfaces give no return (distance 0)
  double start_angle_deg = 17.0;      // device angle of the first sample of a scan
  uint64_t seed = 1;
  // What the scanner sees (never null): the default room around a fixed scanner, or a world
  // shared with a moving robot.
  std::shared_ptr<const LaserScene> scene = std::make_shared<EmulatedRoom>(EmulatedRoom::Default());

  // model 0x28 (family 2 = A2), firmware 1.29, hardware 7, a fixed serial number.
  static DeviceInfo DefaultInfo();
};

struct RplidarDeviceStats {
  std::map<uint8_t, int64_t> requests;  // per command byte
  int64_t bad_requests = 0;             // dropped by the request parser
  int64_t ignored_requests = 0;         // while silent or booting
  int64_t resets = 0;
  int64_t nodes_sent = 0;
  int64_t capsules_sent = 0;
  int64_t samples_skipped = 0;          // due while the transmitter fell behind
  int64_t garbage_bytes = 0;
  int64_t corrupted_packets = 0;
  int64_t dropped_bytes = 0;
  bool scanning = false;
  bool motor_running = false;
  int pwm = 0;
  std::optional<bool> host_dtr;
  // The last request received, and whether a scan was running when it came.
  uint8_t last_request = 0;
  bool last_request_while_scanning = false;
};

class RplidarDeviceModel {
 public:
  explicit RplidarDeviceModel(const RplidarDeviceOptions& options);

  // Bytes from the host at `now_us` (any monotonic time base, microseconds).
  void OnHostBytes(const uint8_t* data, size_t size, int64_t now_us);
  // The host's DTR line, or nullopt when it cannot be observed.
  void SetHostDtr(std::optional<bool> dtr_asserted, int64_t now_us);
  // Everything the device transmits up to `now_us`, faults applied.
  std::vector<uint8_t> TakeOutput(int64_t now_us);
  // Power lost and back (a replugged USB adapter): idle, motor off, configured health.
  void PowerCycle(int64_t now_us);

  // Faults. Packet faults hit the next scan packets (nodes or capsules).
  void InjectGarbage(size_t bytes);          // random bytes between two packets
  void CorruptPackets(int count);            // capsule: bad checksum; node: lost sync/check bit
  void DropBytes(int count);                 // one byte missing inside each of `count` packets
  void Silence(int64_t duration_us, int64_t now_us);  // transmits nothing, ignores requests
  // Transmits nothing but still carries out requests (SET_MOTOR_PWM 0 stops the motor): a
  // device whose transmit line failed, or one stuck in a state that never answers.
  void Mute(int64_t duration_us, int64_t now_us);
  void SetHealth(const DeviceHealth& health, bool persists_after_reset);

  const RplidarDeviceStats& stats() const { return stats_; }
  // Device angle of the k-th sample of a scan at `sample_us` per sample, before any express
  // correction (for tests).
  double SampleAngleDeg(int64_t k, uint16_t sample_us) const;

 private:
  enum class ScanKind { kNone, kStandard, kExpress };
  void HandleRequest(const Request& request, int64_t now_us);
  void Reply(uint8_t data_type, const std::vector<uint8_t>& data);
  void StartScan(ScanKind kind, bool force, int64_t now_us);
  void UpdateMotor(int64_t now_us);
  bool MotorAtSpeed(int64_t now_us) const;
  void GenerateScan(int64_t now_us);
  void EmitPacket(std::vector<uint8_t> packet, bool express);
  std::vector<uint8_t> StandardNode(int64_t k) const;
  std::vector<uint8_t> ExpressCapsule(int64_t capsule_index, bool start_flag) const;
  // Distance in millimetres at a device angle for sample k measured at `time_us` (0: no
  // return), and its quality.
  double MeasureMm(double device_angle_deg, int64_t k, int64_t time_us, uint8_t* quality) const;
  int64_t SampleTimeUs(int64_t k, uint16_t sample_us) const;
  uint64_t Hash(int64_t k, uint64_t stream) const;
  double Uniform(int64_t k, uint64_t stream) const;

  RplidarDeviceOptions options_;
  RequestParser parser_;
  RplidarDeviceStats stats_;
  DeviceHealth health_;
  bool health_persists_ = false;
  std::vector<uint8_t> output_;

  ScanKind scan_ = ScanKind::kNone;
  bool force_ = false;
  int64_t scan_requested_us_ = 0;
  int64_t epoch_us_ = -1;       // time of sample 0 of the data stream, -1 until it starts
  int64_t next_sample_ = 0;     // standard: next node; express: next capsule * 32
  uint64_t scan_number_ = 0;    // new noise per scan
  bool restart_capsule_ = false;  // the next capsule follows a gap: S bit set

  std::optional<bool> host_dtr_;
  int pwm_ = 0;
  int64_t motor_on_since_us_ = -1;

  int64_t silent_until_us_ = -1;
  bool silence_hears_requests_ = false;  // Mute() rather than Silence()
  int64_t booting_until_us_ = -1;
  bool banner_pending_ = false;

  size_t garbage_pending_ = 0;
  int corrupt_pending_ = 0;
  int drop_pending_ = 0;
  uint64_t fault_counter_ = 0;
};

}  // namespace rplidar
}  // namespace slammtt
