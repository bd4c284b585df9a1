// The RPLIDAR A2 device session: one device link, from open to a clean stop, reporting a
// LaserScan per revolution and the LidarStatus about once a second and on every change of state
// (rplidar_session_output.h). Pure: the link factory, the clock, the output and the log are
// given; it knows no message and no bus (the program's adapter, rplidar_driver.h, publishes
// LASER_SCAN and LIDAR_STATUS).
//
// Lifecycle (protocol document "Communication mechanism"; the SDK's order, our notes in
// ../shared/design/protocols/rplidar.md):
//   open the link (serial or TCP) -> STOP (a scan may still run from a previous session) and
//   drop what is in flight -> GET_INFO -> GET_HEALTH: on a warning or an error, RESET once
//   (the recovery the vendor documents) and start over; an error that persists after the reset
//   refuses the scan ("health error, code 0x...") and is re-checked after the longest backoff
//   without another reset; a warning that persists is logged and scanning goes on ->
//   GET_SAMPLERATE (informative) -> motor on: DTR cleared (A1/A2 through the USB adapter), or
//   SET_MOTOR_PWM when GET_ACC_BOARD_FLAG says the accessory board takes it -> SCAN,
//   FORCE_SCAN or legacy EXPRESS_SCAN (firmware >= 1.17; older firmware gets the standard scan,
//   with a warning) -> decode, assemble revolutions, publish.
// A link error (unplugged, closed, write timeout), a device that stops answering, or no scan
// data for data_timeout_ms closes the link, is reported (LidarStatus state "reconnecting",
// last_error) and the link is reopened after a backoff doubling from reconnect_initial_ms to
// reconnect_max_ms. On shutdown: STOP, then the motor off (PWM 0 or DTR asserted), status
// "stopped", on every exit path: a stop requested while the driver waits for a reply ends the
// wait at once; one requested while the link is closed (the backoff after a link error)
// reopens it once to stop the motor; PWM 0 is sent whenever any session of the process started
// the motor by PWM (the device's STOP does not stop the motor).
//
// Time: utime of a LaserScan is the host time (DriverClock::NowUtime) at which the bytes of
// its first sample arrived, read right after the read that returned them; scan_duration_us
// runs to the arrival of its last sample. Nothing is subtracted for the transmission delay
// (about 0.4 ms for a standard node, 7 ms for an express capsule at 115200 baud) or the
// express decoder's one-capsule wait: the stamp is when the host had the data.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/common/driver_log.h"
#include "drivers/common/reconnect_backoff.h"
#include "drivers/rplidar/rplidar_driver_options.h"
#include "drivers/rplidar/rplidar_protocol.h"
#include "drivers/rplidar/rplidar_scan_decoder.h"
#include "drivers/rplidar/rplidar_session_output.h"

namespace slammtt {
namespace rplidar {

class RplidarSession {
 public:
  // Opens a link: OpenByteStream(port, baud) in the program, something else in tests.
  using StreamFactory = std::function<std::unique_ptr<ByteStream>()>;

  // `clock`, `output` and `log` (may be null: no lines) outlive the session. Throws
  // std::invalid_argument, one line naming the key, for options CheckRplidarSessionOptions
  // refuses.
  RplidarSession(const RplidarDriverOptions& options, StreamFactory open_stream,
                 DriverClock* clock, RplidarSessionOutput* output, DriverLog* log);

  // Runs until should_stop() returns true (checked at least every 50 ms), then stops the scan
  // and the motor if the link is up. Never throws for device or link trouble: it reports and
  // retries. Any other exception (from the output, say) is passed on after the scan and the
  // motor were stopped.
  void Run(const std::function<bool()>& should_stop);

  // The status as last reported (utime: when).
  const LidarStatus& status() const { return status_; }

 private:
  enum class SessionEnd { kStopRequested, kHealthRefused };
  SessionEnd Session(ByteStream& stream, const std::function<bool()>& should_stop);
  void StopDevice(ByteStream& stream);
  void Send(ByteStream& stream, const std::vector<uint8_t>& request);
  // Reads until a descriptor of `data_type` and its `length` bytes (single reply); for a
  // multiple reply returns after the descriptor with the bytes that followed it in `leftover`.
  std::vector<uint8_t> ReadReply(ByteStream& stream, uint8_t data_type, const char* what,
                                 int timeout_ms, std::vector<uint8_t>* leftover = nullptr);
  void StartMotor(ByteStream& stream);
  void HandleData(const uint8_t* data, size_t size, int64_t arrival_utime);
  void PublishScan(const std::vector<ScanSample>& revolution);
  void SetState(LidarState state);
  // Lines for the people running the driver (driver_log.h).
  DriverLogLine LogDebug() { return DriverLogLine(log_, DriverLogLevel::kDebug); }
  DriverLogLine LogInfo() { return DriverLogLine(log_, DriverLogLevel::kInfo); }
  DriverLogLine LogWarning() { return DriverLogLine(log_, DriverLogLevel::kWarning); }
  DriverLogLine LogError() { return DriverLogLine(log_, DriverLogLevel::kError); }
  void MaybePublishStatus(bool force);
  bool SleepMs(int64_t ms, const std::function<bool()>& should_stop);

  RplidarDriverOptions options_;
  StreamFactory open_stream_;
  DriverClock* clock_;
  RplidarSessionOutput* output_;
  DriverLog* log_;

  ReconnectBackoff backoff_;
  bool reset_done_ = false;      // one RESET per health problem, until health is good again
  bool use_pwm_ = false;         // a session of this process started the motor by PWM
  bool motor_may_run_ = false;   // started and not stopped since
  const std::function<bool()>* should_stop_ = nullptr;  // during Run(), for reply waits
  ScanMode active_mode_ = ScanMode::kExpress;  // the configured mode unless the firmware lacks it
  StandardNodeDecoder standard_decoder_;
  ExpressCapsuleDecoder express_decoder_;
  RevolutionAssembler assembler_;
  std::vector<ScanSample> samples_;
  int64_t sequence_ = 0;
  std::deque<int64_t> revolution_times_us_;  // monotonic, for scan_rate_hz
  int64_t last_status_us_ = -1;
  LidarStatus status_;
};

}  // namespace rplidar
}  // namespace slammtt
