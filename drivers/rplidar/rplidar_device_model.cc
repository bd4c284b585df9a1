#include "drivers/rplidar/rplidar_device_model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace slammtt {
namespace rplidar {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Express corrections drawn in [0, 16) eighths of a degree: enough to exercise the decoder's
// dtheta bits (the unit tests cover the full 6-bit range) without scrambling the beam order.
constexpr int kMaxDthetaQ3 = 16;

uint64_t SplitMix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

int64_t FloorShift(int64_t value, int bits) {
  const int64_t divisor = int64_t{1} << bits;
  int64_t quotient = value / divisor;
  if (value % divisor != 0 && value < 0) --quotient;
  return quotient;
}

uint16_t AngleQ6(double degrees) {
  int64_t q6 = static_cast<int64_t>(std::floor(degrees * 64.0)) % kFullTurnQ6;
  if (q6 < 0) q6 += kFullTurnQ6;
  return static_cast<uint16_t>(q6);
}

}  // namespace

DeviceInfo RplidarDeviceOptions::DefaultInfo() {
  DeviceInfo info;
  info.model = 0x28;
  info.firmware_major = 1;
  info.firmware_minor = 29;
  info.hardware = 7;
  const uint8_t serial[16] = {0x5E, 0xA1, 0x3C, 0x00, 0x1D, 0x42, 0x9B, 0x27,
                              0x80, 0x64, 0xC3, 0x11, 0x07, 0xF2, 0x38, 0x2A};
  std::memcpy(info.serial_number.data(), serial, sizeof serial);
  return info;
}

RplidarDeviceModel::RplidarDeviceModel(const RplidarDeviceOptions& options)
    : options_(options), health_(options.health),
      health_persists_(options.health_persists_after_reset) {}

uint64_t RplidarDeviceModel::Hash(int64_t k, uint64_t stream) const {
  return SplitMix64(options_.seed ^ SplitMix64(scan_number_ * 0x100000001B3ull + stream) ^
                    SplitMix64(static_cast<uint64_t>(k)));
}

double RplidarDeviceModel::Uniform(int64_t k, uint64_t stream) const {
  return static_cast<double>(Hash(k, stream) >> 11) * (1.0 / 9007199254740992.0);
}

double RplidarDeviceModel::SampleAngleDeg(int64_t k, uint16_t sample_us) const {
  const double degrees = options_.start_angle_deg + static_cast<double>(k) * sample_us * 1e-6 *
                                                        options_.rotation_hz * 360.0;
  return std::fmod(degrees, 360.0);
}

int64_t RplidarDeviceModel::SampleTimeUs(int64_t k, uint16_t sample_us) const {
  return epoch_us_ + k * sample_us;
}

double RplidarDeviceModel::MeasureMm(double device_angle_deg, int64_t k, int64_t time_us,
                                     uint8_t* quality) const {
  *quality = 0;
  const std::optional<SceneReturn> surface = options_.scene->Cast(device_angle_deg, time_us);
  if (!surface || surface->range_m > options_.max_range_m) return 0.0;
  if (surface->dropout_probability > 0.0 && Uniform(k, 4) < surface->dropout_probability) {
    return 0.0;
  }
  const double range_m = surface->range_m;
  // Box-Muller from two hashed uniforms: the same k always gets the same noise.
  const double u1 = std::max(Uniform(k, 1), 1e-12);
  const double u2 = Uniform(k, 2);
  const double noise = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  const double mm = (range_m + options_.range_noise_m * noise) * 1000.0;
  if (mm <= 1.0) return 0.0;
  *quality = static_cast<uint8_t>(std::clamp(60 - static_cast<int>(range_m * 3.0), 10, 63));
  return mm;
}

void RplidarDeviceModel::OnHostBytes(const uint8_t* data, size_t size, int64_t now_us) {
  std::vector<Request> requests;
  parser_.Feed(data, size, &requests);
  stats_.bad_requests = parser_.bad_checksums();
  for (const Request& request : requests) {
    const bool silent =
        silent_until_us_ >= 0 && now_us < silent_until_us_ && !silence_hears_requests_;
    const bool booting = booting_until_us_ >= 0 && now_us < booting_until_us_;
    if (silent || booting) {
      ++stats_.ignored_requests;
      continue;
    }
    HandleRequest(request, now_us);
  }
}

void RplidarDeviceModel::Reply(uint8_t data_type, const std::vector<uint8_t>& data) {
  const std::vector<uint8_t> descriptor = EncodeDescriptor(DescriptorFor(data_type));
  output_.insert(output_.end(), descriptor.begin(), descriptor.end());
  output_.insert(output_.end(), data.begin(), data.end());
}

void RplidarDeviceModel::HandleRequest(const Request& request, int64_t now_us) {
  ++stats_.requests[request.command];
  stats_.last_request = request.command;
  stats_.last_request_while_scanning = scan_ != ScanKind::kNone;
  if (request.command != kSetMotorPwm) scan_ = ScanKind::kNone;
  switch (request.command) {
    case kStop:
      break;
    case kReset:
      ++stats_.resets;
      booting_until_us_ = now_us + options_.reset_boot_us;
      banner_pending_ = true;
      pwm_ = 0;
      if (!health_persists_) health_ = DeviceHealth();
      output_.clear();
      break;
    case kScan:
      StartScan(ScanKind::kStandard, false, now_us);
      break;
    case kForceScan:
      StartScan(ScanKind::kStandard, true, now_us);
      break;
    case kExpressScan:
      if (request.payload.size() == 5 && request.payload[0] == 0) {
        StartScan(ScanKind::kExpress, false, now_us);
      }
      break;
    case kGetInfo:
      Reply(kAnswerDeviceInfo, EncodeDeviceInfo(options_.info));
      break;
    case kGetHealth:
      Reply(kAnswerDeviceHealth, EncodeDeviceHealth(health_));
      break;
    case kGetSampleRate:
      Reply(kAnswerSampleRate,
            EncodeSampleRate({options_.standard_sample_us, options_.express_sample_us}));
      break;
    case kGetAccBoardFlag:
      if (request.payload.size() == 4) {
        Reply(kAnswerAccBoardFlag,
              EncodeAccBoardFlag(options_.accessory_board ? kAccBoardMotorPwmSupported : 0));
      }
      break;
    case kSetMotorPwm:
      if (options_.accessory_board && request.payload.size() == 2) {
        pwm_ = std::min(1023, request.payload[0] | (request.payload[1] << 8));
        UpdateMotor(now_us);
      }
      break;
    default:
      break;  // GET_LIDAR_CONF and anything unknown: no reply, as older firmware
  }
  stats_.scanning = scan_ != ScanKind::kNone;
  stats_.pwm = pwm_;
}

void RplidarDeviceModel::StartScan(ScanKind kind, bool force, int64_t now_us) {
  scan_ = kind;
  force_ = force;
  scan_requested_us_ = now_us;
  epoch_us_ = -1;
  restart_capsule_ = false;
  next_sample_ = 0;
  ++scan_number_;
  const ResponseDescriptor descriptor = DescriptorFor(
      kind == ScanKind::kExpress ? kAnswerMeasurementCapsuled : kAnswerMeasurement);
  const std::vector<uint8_t> bytes = EncodeDescriptor(descriptor);
  output_.insert(output_.end(), bytes.begin(), bytes.end());
}

void RplidarDeviceModel::SetHostDtr(std::optional<bool> dtr_asserted, int64_t now_us) {
  host_dtr_ = dtr_asserted;
  stats_.host_dtr = dtr_asserted;
  UpdateMotor(now_us);
}

void RplidarDeviceModel::UpdateMotor(int64_t now_us) {
  const bool running = options_.accessory_board ? pwm_ > 0 : !(host_dtr_ && *host_dtr_);
  if (running && motor_on_since_us_ < 0) motor_on_since_us_ = now_us;
  if (!running) {
    motor_on_since_us_ = -1;
    epoch_us_ = -1;  // the data stream stops with the motor and starts over with it
  }
  stats_.motor_running = running;
}

bool RplidarDeviceModel::MotorAtSpeed(int64_t now_us) const {
  return motor_on_since_us_ >= 0 && now_us - motor_on_since_us_ >= options_.spin_up_us;
}

void RplidarDeviceModel::PowerCycle(int64_t now_us) {
  parser_.Reset();
  output_.clear();
  scan_ = ScanKind::kNone;
  pwm_ = 0;
  health_ = options_.health;
  health_persists_ = options_.health_persists_after_reset;
  silent_until_us_ = -1;
  booting_until_us_ = -1;
  banner_pending_ = false;
  garbage_pending_ = 0;
  corrupt_pending_ = 0;
  drop_pending_ = 0;
  host_dtr_.reset();
  motor_on_since_us_ = -1;
  UpdateMotor(now_us);
  stats_.scanning = false;
  stats_.pwm = 0;
}

void RplidarDeviceModel::InjectGarbage(size_t bytes) { garbage_pending_ += bytes; }
void RplidarDeviceModel::CorruptPackets(int count) { corrupt_pending_ += count; }
void RplidarDeviceModel::DropBytes(int count) { drop_pending_ += count; }
void RplidarDeviceModel::Silence(int64_t duration_us, int64_t now_us) {
  silent_until_us_ = now_us + duration_us;
  silence_hears_requests_ = false;
}
void RplidarDeviceModel::Mute(int64_t duration_us, int64_t now_us) {
  silent_until_us_ = now_us + duration_us;
  silence_hears_requests_ = true;
}
void RplidarDeviceModel::SetHealth(const DeviceHealth& health, bool persists_after_reset) {
  health_ = health;
  health_persists_ = persists_after_reset;
}

std::vector<uint8_t> RplidarDeviceModel::TakeOutput(int64_t now_us) {
  UpdateMotor(now_us);
  if (silent_until_us_ >= 0 && now_us < silent_until_us_) {
    output_.clear();
    if (epoch_us_ >= 0) {
      // Time runs on while the device is silent: what it measured is lost, not queued.
      const uint16_t sample_us =
          scan_ == ScanKind::kExpress ? options_.express_sample_us : options_.standard_sample_us;
      const int64_t due = (now_us - epoch_us_) / sample_us;
      if (due > next_sample_) {
        stats_.samples_skipped += due - next_sample_;
        next_sample_ = scan_ == ScanKind::kExpress ? due / 32 * 32 : due;
        restart_capsule_ = true;
      }
    }
    return {};
  }
  if (booting_until_us_ >= 0 && now_us >= booting_until_us_) {
    booting_until_us_ = -1;
    if (banner_pending_) {
      // A reboot prints a text banner (the real A2 prints its firmware and hardware versions).
      const std::string banner = "RP LIDAR System.\r\nFirmware Ver " +
                                 std::to_string(options_.info.firmware_major) + "." +
                                 std::to_string(options_.info.firmware_minor) +
                                 " - slammtt emulator, HW Ver " +
                                 std::to_string(options_.info.hardware) + "\r\n";
      output_.insert(output_.end(), banner.begin(), banner.end());
      banner_pending_ = false;
    }
  }
  for (; garbage_pending_ > 0; --garbage_pending_) {
    output_.push_back(static_cast<uint8_t>(Hash(static_cast<int64_t>(fault_counter_++), 7)));
    ++stats_.garbage_bytes;
  }
  GenerateScan(now_us);
  std::vector<uint8_t> out;
  out.swap(output_);
  return out;
}

void RplidarDeviceModel::GenerateScan(int64_t now_us) {
  if (scan_ == ScanKind::kNone || booting_until_us_ >= 0) return;
  const bool ready = force_ ? motor_on_since_us_ >= 0 : MotorAtSpeed(now_us);
  if (!ready) return;
  if (epoch_us_ < 0) {
    epoch_us_ = now_us;
    next_sample_ = 0;
  }
  const bool express = scan_ == ScanKind::kExpress;
  const uint16_t sample_us = express ? options_.express_sample_us : options_.standard_sample_us;
  const int64_t due = (now_us - epoch_us_) / sample_us;
  // A transmitter that fell far behind (a stalled emulator) skips ahead instead of bursting:
  // at most one revolution of backlog is sent. Express capsules after a gap restart the scan
  // (S bit), as the device does, so no host interpolates across the gap.
  const int64_t per_revolution =
      static_cast<int64_t>(1e6 / (options_.rotation_hz * sample_us));
  const int64_t backlog_limit = std::max<int64_t>(64, per_revolution);
  if (due - next_sample_ > backlog_limit) {
    int64_t resume = due - backlog_limit;
    if (express) resume = resume / 32 * 32;
    stats_.samples_skipped += resume - next_sample_;
    next_sample_ = resume;
    restart_capsule_ = true;
  }
  if (express) {
    // Capsule i carries samples 32 i .. 32 i + 31 and leaves once they are measured.
    while (next_sample_ + 32 <= due) {
      const int64_t index = next_sample_ / 32;
      EmitPacket(ExpressCapsule(index, index == 0 || restart_capsule_), true);
      restart_capsule_ = false;
      next_sample_ += 32;
    }
  } else {
    for (; next_sample_ < due; ++next_sample_) EmitPacket(StandardNode(next_sample_), false);
  }
}

void RplidarDeviceModel::EmitPacket(std::vector<uint8_t> packet, bool express) {
  if (corrupt_pending_ > 0) {
    --corrupt_pending_;
    ++stats_.corrupted_packets;
    if (express) {
      packet[40] ^= 0x5A;  // any change of a checked byte breaks the XOR checksum
    } else {
      packet[0] |= 0x3;    // S and !S both set: the sync bit is lost
    }
  }
  if (drop_pending_ > 0 && packet.size() > 2) {
    --drop_pending_;
    ++stats_.dropped_bytes;
    packet.erase(packet.begin() + static_cast<std::ptrdiff_t>(packet.size() / 2));
  }
  output_.insert(output_.end(), packet.begin(), packet.end());
  if (express) {
    ++stats_.capsules_sent;
  } else {
    ++stats_.nodes_sent;
  }
}

std::vector<uint8_t> RplidarDeviceModel::StandardNode(int64_t k) const {
  const uint16_t angle_q6 = AngleQ6(SampleAngleDeg(k, options_.standard_sample_us));
  const bool start =
      k > 0 && angle_q6 < AngleQ6(SampleAngleDeg(k - 1, options_.standard_sample_us));
  uint8_t quality = 0;
  const double mm =
      MeasureMm(angle_q6 / 64.0, k, SampleTimeUs(k, options_.standard_sample_us), &quality);
  const uint16_t distance_q2 = static_cast<uint16_t>(std::min(65535.0, std::round(mm * 4.0)));
  return {static_cast<uint8_t>((quality << 2) | (start ? 0x1 : 0x2)),
          static_cast<uint8_t>(((angle_q6 & 0x7F) << 1) | 0x1),
          static_cast<uint8_t>(angle_q6 >> 7), static_cast<uint8_t>(distance_q2 & 0xFF),
          static_cast<uint8_t>(distance_q2 >> 8)};
}

std::vector<uint8_t> RplidarDeviceModel::ExpressCapsule(int64_t capsule_index,
                                                        bool start_flag) const {
  const int64_t first = capsule_index * 32;
  const uint16_t start_q6 = AngleQ6(SampleAngleDeg(first, options_.express_sample_us));
  const uint16_t next_q6 = AngleQ6(SampleAngleDeg(first + 32, options_.express_sample_us));
  // The host interpolates between this start angle and the next one (handler_capsules.cpp);
  // the device measures each sample where that interpolation, minus its dtheta, points.
  const int64_t start_q8 = int64_t{start_q6} << 2;
  const int64_t next_q8 = int64_t{next_q6} << 2;
  int64_t diff_q8 = next_q8 - start_q8;
  if (start_q8 > next_q8) diff_q8 += int64_t{360} << 8;
  const int64_t increment_q16 = diff_q8 << 3;
  std::vector<uint8_t> capsule(kExpressCapsuleSize, 0);
  const uint16_t start_word = static_cast<uint16_t>(start_q6 | (start_flag ? 0x8000 : 0));
  capsule[2] = static_cast<uint8_t>(start_word & 0xFF);
  capsule[3] = static_cast<uint8_t>(start_word >> 8);
  int64_t angle_q16 = start_q8 << 8;
  for (int cabin = 0; cabin < 16; ++cabin) {
    uint8_t* bytes = capsule.data() + 4 + cabin * 5;
    uint8_t offsets = 0;
    for (int half = 0; half < 2; ++half) {
      const int64_t k = first + cabin * 2 + half;
      const int dtheta_q3 = static_cast<int>(Uniform(k, 3) * kMaxDthetaQ3);
      int64_t angle_q6 = FloorShift(angle_q16 - (int64_t{dtheta_q3} << 13), 10);
      if (angle_q6 < 0) angle_q6 += kFullTurnQ6;
      if (angle_q6 >= kFullTurnQ6) angle_q6 -= kFullTurnQ6;
      angle_q16 += increment_q16;
      uint8_t quality = 0;
      const double mm = MeasureMm(static_cast<double>(angle_q6) / 64.0, k,
                                  SampleTimeUs(k, options_.express_sample_us), &quality);
      const uint16_t distance_mm = static_cast<uint16_t>(std::min(16383.0, std::round(mm)));
      const uint16_t field = static_cast<uint16_t>((distance_mm << 2) | ((dtheta_q3 >> 4) & 0x3));
      bytes[half * 2] = static_cast<uint8_t>(field & 0xFF);
      bytes[half * 2 + 1] = static_cast<uint8_t>(field >> 8);
      offsets = static_cast<uint8_t>(offsets | ((dtheta_q3 & 0xF) << (half * 4)));
    }
    bytes[4] = offsets;
  }
  uint8_t checksum = 0;
  for (size_t i = 2; i < kExpressCapsuleSize; ++i) checksum ^= capsule[i];
  capsule[0] = static_cast<uint8_t>(0xA0 | (checksum & 0xF));
  capsule[1] = static_cast<uint8_t>(0x50 | (checksum >> 4));
  return capsule;
}

}  // namespace rplidar
}  // namespace slammtt
