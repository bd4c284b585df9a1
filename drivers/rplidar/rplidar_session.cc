#include "drivers/rplidar/rplidar_session.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/checked_options.h"
namespace slammtt {
namespace rplidar {
namespace {

// A device that did not answer in time: the link is reopened, unless the question was optional.
class NoReply : public LinkError {
 public:
  using LinkError::LinkError;
};

// A stop was requested while the driver waited for a reply: the session ends at once (the
// motor is stopped on the way out), without waiting out the reply's timeout.
class StopRequested : public std::exception {
 public:
  const char* what() const noexcept override { return "stop requested"; }
};

constexpr size_t kMaxSingleReply = 1024;
constexpr int kReadSliceMs = 20;
constexpr size_t kMaxRevolutionTimes = 11;

std::string Hex4(int value) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", value & 0xFFFF);
  return text;
}

}  // namespace

RplidarSession::RplidarSession(const RplidarDriverOptions& options, StreamFactory open_stream,
                               DriverClock* clock, RplidarSessionOutput* output, DriverLog* log)
    : options_(CheckedOptions(options, &CheckRplidarSessionOptions, "RPLIDAR driver options")),
      open_stream_(std::move(open_stream)),
      clock_(clock),
      output_(output),
      log_(log),
      backoff_(options.reconnect_initial_ms, options.reconnect_max_ms),
      standard_decoder_(options.decoder) {
  status_.connected = false;
  status_.state = LidarState::kConnecting;
  status_.endpoint = options_.port;
  status_.scan_mode = options_.scan_mode;
}

bool RplidarSession::SleepMs(int64_t ms, const std::function<bool()>& should_stop) {
  const int64_t end = clock_->NowMonotonicUs() + ms * 1000;
  while (!should_stop()) {
    const int64_t left_us = end - clock_->NowMonotonicUs();
    if (left_us <= 0) return false;
    clock_->SleepUs(std::min<int64_t>(left_us, 20000));
  }
  return true;
}

void RplidarSession::Run(const std::function<bool()>& should_stop) {
  should_stop_ = &should_stop;
  MaybePublishStatus(true);
  while (!should_stop()) {
    std::unique_ptr<ByteStream> stream;
    try {
      SetState(LidarState::kConnecting);
      stream = open_stream_();
      status_.connected = true;
      status_.endpoint = stream->Describe();
      SessionEnd end = SessionEnd::kStopRequested;
      try {
        end = Session(*stream, should_stop);
      } catch (const StopRequested&) {
        end = SessionEnd::kStopRequested;
      }
      if (end == SessionEnd::kStopRequested) {
        StopDevice(*stream);
        break;
      }
      // Health refused: close, check again after the longest backoff (no second reset).
      stream.reset();
      status_.connected = false;
      MaybePublishStatus(true);
      SleepMs(options_.reconnect_max_ms, should_stop);
    } catch (const LinkError& e) {
      stream.reset();
      status_.connected = false;
      status_.last_error = e.what();
      ++status_.reconnects;
      standard_decoder_.Reset();
      express_decoder_.Reset();
      assembler_.Reset();
      const int64_t delay_ms = backoff_.NextDelayMs();
      LogWarning() << e.what() << "; reopening in " << delay_ms << " ms";
      SetState(LidarState::kReconnecting);
      SleepMs(delay_ms, should_stop);
    } catch (...) {
      // Anything else (the bus failing to publish, say) ends the process: the device must not
      // go on scanning with its motor turning until someone restarts us.
      if (stream) StopDevice(*stream);
      should_stop_ = nullptr;
      throw;
    }
  }
  // Stopped while the link was closed (in the backoff after a link error, or between a failed
  // session and the next): a device that lost its link, or stopped answering, may still turn
  // its motor, which STOP alone never stops. Reopen once and stop it.
  if (motor_may_run_) {
    try {
      std::unique_ptr<ByteStream> stream = open_stream_();
      LogInfo() << "reopened " << stream->Describe() << " to stop the motor";
      StopDevice(*stream);
    } catch (const LinkError& e) {
      LogWarning() << "could not reopen the link to stop the motor: " << e.what();
    }
  }
  should_stop_ = nullptr;
  status_.connected = false;
  SetState(LidarState::kStopped);
  MaybePublishStatus(true);
}

void RplidarSession::Send(ByteStream& stream, const std::vector<uint8_t>& request) {
  stream.Write(request.data(), request.size(), options_.response_timeout_ms);
}

std::vector<uint8_t> RplidarSession::ReadReply(ByteStream& stream, uint8_t data_type,
                                               const char* what, int timeout_ms,
                                               std::vector<uint8_t>* leftover) {
  const int64_t deadline_us = clock_->NowMonotonicUs() + int64_t{timeout_ms} * 1000;
  std::vector<uint8_t> pending;
  uint8_t buffer[512];
  for (;;) {
    // Skip to the next descriptor sync; whatever precedes it (a reset banner, scan data still
    // in flight) is not ours.
    size_t start = 0;
    while (start + 1 < pending.size() &&
           !(pending[start] == kDescriptorSync1 && pending[start + 1] == kDescriptorSync2)) {
      ++start;
    }
    if (start + 1 >= pending.size() && !pending.empty() && pending.back() != kDescriptorSync1) {
      start = pending.size();
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(start));
    if (pending.size() >= kDescriptorSize) {
      const std::optional<ResponseDescriptor> descriptor = ParseDescriptor(pending.data());
      if (!descriptor || descriptor->data_type != data_type ||
          descriptor->length > kMaxSingleReply) {
        pending.erase(pending.begin());
        continue;
      }
      if (descriptor->mode == SendMode::kMultiple) {
        if (leftover != nullptr) {
          leftover->assign(pending.begin() + kDescriptorSize, pending.end());
        }
        return {};
      }
      if (pending.size() >= kDescriptorSize + descriptor->length) {
        return std::vector<uint8_t>(pending.begin() + kDescriptorSize,
                                    pending.begin() + kDescriptorSize + descriptor->length);
      }
    }
    if (should_stop_ != nullptr && (*should_stop_)()) throw StopRequested();
    const int64_t left_us = deadline_us - clock_->NowMonotonicUs();
    if (left_us <= 0) {
      throw NoReply(stream.Describe() + ": no reply to " + what + " within " +
                    std::to_string(timeout_ms) + " ms");
    }
    const int slice_ms = static_cast<int>(std::min<int64_t>(left_us / 1000 + 1, 50));
    const size_t got = stream.Read(buffer, sizeof buffer, slice_ms);
    pending.insert(pending.end(), buffer, buffer + got);
  }
}

RplidarSession::SessionEnd RplidarSession::Session(ByteStream& stream,
                                                   const std::function<bool()>& should_stop) {
  DeviceInfo info;
  for (;;) {
    // A scan may still run from an earlier session: stop it and drop what is in flight
    // (protocol: wait at least 1 ms after STOP).
    Send(stream, StopRequest());
    if (SleepMs(20, should_stop)) return SessionEnd::kStopRequested;
    stream.FlushInput();

    Send(stream, GetInfoRequest());
    const std::vector<uint8_t> info_bytes =
        ReadReply(stream, kAnswerDeviceInfo, "GET_INFO", options_.response_timeout_ms);
    const std::optional<DeviceInfo> parsed_info =
        ParseDeviceInfo(info_bytes.data(), info_bytes.size());
    if (!parsed_info) throw LinkError(stream.Describe() + ": malformed GET_INFO reply");
    info = *parsed_info;
    status_.model = info.model;
    status_.firmware_major = info.firmware_major;
    status_.firmware_minor = info.firmware_minor;
    status_.hardware = info.hardware;
    status_.serial_number = info.SerialNumberHex();

    Send(stream, GetHealthRequest());
    const std::vector<uint8_t> health_bytes =
        ReadReply(stream, kAnswerDeviceHealth, "GET_HEALTH", options_.response_timeout_ms);
    const std::optional<DeviceHealth> health =
        ParseDeviceHealth(health_bytes.data(), health_bytes.size());
    if (!health) throw LinkError(stream.Describe() + ": malformed GET_HEALTH reply");
    status_.health = *health;
    MaybePublishStatus(true);
    if (health->status == HealthStatus::kGood) {
      reset_done_ = false;
      break;
    }
    const std::string problem = std::string("device health ") + HealthName(health->status) +
                                ", code " + Hex4(health->error_code);
    if (!reset_done_) {
      // The vendor's recovery: a software reset (protocol document, RESET; SDK reset()).
      LogWarning() << problem << ": resetting the device once";
      reset_done_ = true;
      Send(stream, ResetRequest());
      if (SleepMs(options_.reset_wait_ms, should_stop)) return SessionEnd::kStopRequested;
      stream.FlushInput();
      continue;
    }
    if (health->status == HealthStatus::kError) {
      status_.last_error = problem + " persists after a reset: refusing to scan";
      LogError() << status_.last_error << "; checking again in " << options_.reconnect_max_ms
                 << " ms";
      SetState(LidarState::kHealthError);
      return SessionEnd::kHealthRefused;
    }
    LogWarning() << problem << " persists after a reset: scanning anyway";
    break;
  }
  LogInfo() << "connected to " << stream.Describe() << ": model " << Hex4(info.model)
            << ", firmware " << int{info.firmware_major} << "." << int{info.firmware_minor}
            << ", hardware " << int{info.hardware} << ", serial " << info.SerialNumberHex()
            << ", health " << HealthName(status_.health->status);

  // Firmware >= 1.17 answers GET_SAMPLERATE and knows EXPRESS_SCAN (sl_lidar_cmd.h).
  const bool firmware_1_17 =
      info.firmware_major > 1 || (info.firmware_major == 1 && info.firmware_minor >= 17);
  if (firmware_1_17) {
    try {
      Send(stream, GetSampleRateRequest());
      const std::vector<uint8_t> rate_bytes =
          ReadReply(stream, kAnswerSampleRate, "GET_SAMPLERATE", options_.response_timeout_ms);
      if (const auto rate = ParseSampleRate(rate_bytes.data(), rate_bytes.size())) {
        LogDebug() << "sample time: standard " << rate->standard_us << " us, express "
                   << rate->express_us << " us";
      }
    } catch (const NoReply& e) {
      LogDebug() << e.what();
    }
  }

  StartMotor(stream);
  if (should_stop()) return SessionEnd::kStopRequested;

  bool express = options_.scan_mode == ScanMode::kExpress;
  if (express && !firmware_1_17) {
    LogWarning() << "firmware " << int{info.firmware_major} << "." << int{info.firmware_minor}
                 << " has no express scan (needs 1.17): using the standard scan";
    express = false;
  }
  active_mode_ = express ? ScanMode::kExpress : ScanMode::kStandard;
  status_.scan_mode = active_mode_;
  Send(stream, express ? ExpressScanRequest()
                       : (options_.force_scan ? ForceScanRequest() : ScanRequest()));
  std::vector<uint8_t> leftover;
  ReadReply(stream, express ? kAnswerMeasurementCapsuled : kAnswerMeasurement,
            express ? "EXPRESS_SCAN" : "SCAN", options_.response_timeout_ms, &leftover);
  standard_decoder_.Reset();
  express_decoder_.Reset();
  assembler_.Reset();
  revolution_times_us_.clear();
  SetState(LidarState::kScanning);
  LogInfo() << "scanning (" << ScanModeName(active_mode_) << ")";
  backoff_.Reset();

  int64_t last_samples_us = clock_->NowMonotonicUs();
  int64_t samples_before = status_.nodes_decoded;
  bool had_samples = false;
  if (!leftover.empty()) HandleData(leftover.data(), leftover.size(), clock_->NowUtime());
  uint8_t buffer[4096];
  while (!should_stop()) {
    const size_t got = stream.Read(buffer, sizeof buffer, kReadSliceMs);
    const int64_t now_mono = clock_->NowMonotonicUs();
    if (got > 0) HandleData(buffer, got, clock_->NowUtime());
    if (status_.nodes_decoded != samples_before) {
      samples_before = status_.nodes_decoded;
      last_samples_us = now_mono;
      had_samples = true;
    }
    const int limit_ms = had_samples ? options_.data_timeout_ms : options_.first_data_timeout_ms;
    if (now_mono - last_samples_us > int64_t{limit_ms} * 1000) {
      throw LinkError(stream.Describe() + ": no valid scan data for " +
                      std::to_string(limit_ms) + " ms");
    }
    MaybePublishStatus(false);
  }
  return SessionEnd::kStopRequested;
}

void RplidarSession::StartMotor(ByteStream& stream) {
  MotorControl control = options_.motor_control;
  if (control == MotorControl::kAuto) {
    control = MotorControl::kDtr;
    // A2 and A3 (model family 2..5) may carry the accessory board (sl_lidar_driver.cpp
    // checkMotorCtrlSupport); A1 has none.
    const int family = status_.model >> 4;
    if (family >= 2) {
      try {
        Send(stream, GetAccBoardFlagRequest());
        const std::vector<uint8_t> flag_bytes = ReadReply(
            stream, kAnswerAccBoardFlag, "GET_ACC_BOARD_FLAG", options_.response_timeout_ms);
        const auto flag = ParseAccBoardFlag(flag_bytes.data(), flag_bytes.size());
        if (flag && (*flag & kAccBoardMotorPwmSupported) != 0) control = MotorControl::kPwm;
      } catch (const NoReply& e) {
        LogDebug() << e.what() << ": motor through DTR";
      }
    }
  }
  switch (control) {
    case MotorControl::kPwm:
      Send(stream, SetMotorPwmRequest(static_cast<uint16_t>(options_.motor_pwm)));
      use_pwm_ = true;
      break;
    case MotorControl::kDtr:
      stream.SetDtr(false);  // DTR deasserted = motor on (SDK setMotorSpeed for A1/A2)
      break;
    default:
      break;
  }
  motor_may_run_ = control != MotorControl::kNone;
  LogDebug() << "motor "
             << (control == MotorControl::kPwm ? "PWM " + std::to_string(options_.motor_pwm)
                                               : control == MotorControl::kDtr ? "on (DTR)"
                                                                               : "left alone");
}

void RplidarSession::StopDevice(ByteStream& stream) {
  try {
    Send(stream, StopRequest());
    clock_->SleepUs(2000);
    // The device's STOP ends the scan, not the motor. use_pwm_ remembers how any session of
    // this process started it, so a stop before this session's StartMotor still sends PWM 0.
    if (use_pwm_ || options_.motor_control == MotorControl::kPwm) {
      Send(stream, SetMotorPwmRequest(0));
    } else if (options_.motor_control != MotorControl::kNone) {
      stream.SetDtr(true);  // DTR asserted = motor off
    }
    motor_may_run_ = false;
    LogInfo() << "scan stopped, motor off";
  } catch (const LinkError& e) {
    LogWarning() << "could not stop the device: " << e.what();
  }
}

void RplidarSession::HandleData(const uint8_t* data, size_t size, int64_t arrival_utime) {
  samples_.clear();
  if (active_mode_ == ScanMode::kExpress) {
    express_decoder_.Feed(data, size, arrival_utime, &samples_);
  } else {
    standard_decoder_.Feed(data, size, arrival_utime, &samples_);
  }
  for (const ScanSample& sample : samples_) {
    if (auto revolution = assembler_.Add(sample)) PublishScan(*revolution);
  }
  const DecoderCounters& a = standard_decoder_.counters();
  const DecoderCounters& b = express_decoder_.counters();
  status_.nodes_decoded = a.samples + b.samples;
  status_.resyncs = a.resyncs + b.resyncs;
  status_.checksum_errors = a.checksum_errors + b.checksum_errors;
}

void RplidarSession::PublishScan(const std::vector<ScanSample>& revolution) {
  Beams beams = ConvertRevolution(revolution, options_.beams);
  LaserScan scan;
  scan.utime = revolution.front().arrival_us;
  scan.sequence = sequence_++;
  scan.scan_duration_us = revolution.back().arrival_us - revolution.front().arrival_us;
  scan.range_min_m = options_.beams.range_min_m;
  scan.range_max_m = options_.beams.range_max_m;
  scan.beams = std::move(beams);
  output_->OnLaserScan(scan);
  ++status_.scans_published;
  revolution_times_us_.push_back(clock_->NowMonotonicUs());
  while (revolution_times_us_.size() > kMaxRevolutionTimes) revolution_times_us_.pop_front();
  if (revolution_times_us_.size() >= 2) {
    const double span_s =
        static_cast<double>(revolution_times_us_.back() - revolution_times_us_.front()) * 1e-6;
    if (span_s > 0.0) {
      status_.scan_rate_hz = static_cast<double>(revolution_times_us_.size() - 1) / span_s;
    }
  }
}

void RplidarSession::SetState(LidarState state) {
  if (status_.state == state) return;
  status_.state = state;
  MaybePublishStatus(true);
}

void RplidarSession::MaybePublishStatus(bool force) {
  const int64_t now = clock_->NowMonotonicUs();
  const int64_t period_us = static_cast<int64_t>(options_.status_period_s * 1e6);
  if (!force && last_status_us_ >= 0 && now - last_status_us_ < period_us) return;
  last_status_us_ = now;
  if (status_.state != LidarState::kScanning) status_.scan_rate_hz = 0.0;
  status_.utime = clock_->NowUtime();
  output_->OnLidarStatus(status_);
}

}  // namespace rplidar
}  // namespace slammtt
