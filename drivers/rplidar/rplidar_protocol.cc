#include "drivers/rplidar/rplidar_protocol.h"

#include <cstdio>

namespace slammtt {
namespace rplidar {
namespace {

uint16_t ReadU16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
uint32_t ReadU32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
         (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}
void PutU16(std::vector<uint8_t>* out, uint16_t value) {
  out->push_back(static_cast<uint8_t>(value & 0xFF));
  out->push_back(static_cast<uint8_t>(value >> 8));
}
void PutU32(std::vector<uint8_t>* out, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out->push_back(static_cast<uint8_t>(value >> shift));
}

}  // namespace

std::vector<uint8_t> EncodeRequest(uint8_t command, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> packet = {kRequestSync, command};
  if (payload.empty() && (command & 0x80) == 0) return packet;
  packet.push_back(static_cast<uint8_t>(payload.size()));
  packet.insert(packet.end(), payload.begin(), payload.end());
  uint8_t checksum = 0;
  for (uint8_t byte : packet) checksum ^= byte;
  packet.push_back(checksum);
  return packet;
}

std::vector<uint8_t> StopRequest() { return EncodeRequest(kStop); }
std::vector<uint8_t> ResetRequest() { return EncodeRequest(kReset); }
std::vector<uint8_t> ScanRequest() { return EncodeRequest(kScan); }
std::vector<uint8_t> ForceScanRequest() { return EncodeRequest(kForceScan); }
std::vector<uint8_t> ExpressScanRequest() { return EncodeRequest(kExpressScan, {0, 0, 0, 0, 0}); }
std::vector<uint8_t> GetInfoRequest() { return EncodeRequest(kGetInfo); }
std::vector<uint8_t> GetHealthRequest() { return EncodeRequest(kGetHealth); }
std::vector<uint8_t> GetSampleRateRequest() { return EncodeRequest(kGetSampleRate); }
std::vector<uint8_t> SetMotorPwmRequest(uint16_t pwm) {
  std::vector<uint8_t> payload;
  PutU16(&payload, pwm);
  return EncodeRequest(kSetMotorPwm, payload);
}
std::vector<uint8_t> GetAccBoardFlagRequest() { return EncodeRequest(kGetAccBoardFlag, {0, 0, 0, 0}); }

std::optional<ResponseDescriptor> ParseDescriptor(const uint8_t* bytes) {
  if (bytes[0] != kDescriptorSync1 || bytes[1] != kDescriptorSync2) return std::nullopt;
  const uint32_t word = ReadU32(bytes + 2);
  const uint32_t mode = word >> 30;
  if (mode > 1) return std::nullopt;
  ResponseDescriptor descriptor;
  descriptor.length = word & 0x3FFFFFFFu;
  descriptor.mode = mode == 0 ? SendMode::kSingle : SendMode::kMultiple;
  descriptor.data_type = bytes[6];
  return descriptor;
}

std::vector<uint8_t> EncodeDescriptor(const ResponseDescriptor& descriptor) {
  std::vector<uint8_t> bytes = {kDescriptorSync1, kDescriptorSync2};
  PutU32(&bytes, (descriptor.length & 0x3FFFFFFFu) |
                     (static_cast<uint32_t>(descriptor.mode) << 30));
  bytes.push_back(descriptor.data_type);
  return bytes;
}

ResponseDescriptor DescriptorFor(uint8_t data_type) {
  ResponseDescriptor descriptor;
  descriptor.data_type = data_type;
  switch (data_type) {
    case kAnswerDeviceInfo: descriptor.length = kDeviceInfoSize; break;
    case kAnswerDeviceHealth: descriptor.length = kDeviceHealthSize; break;
    case kAnswerSampleRate: descriptor.length = kSampleRateSize; break;
    case kAnswerAccBoardFlag: descriptor.length = kAccBoardFlagSize; break;
    case kAnswerMeasurement:
      descriptor.length = kStandardNodeSize;
      descriptor.mode = SendMode::kMultiple;
      break;
    case kAnswerMeasurementCapsuled:
      descriptor.length = kExpressCapsuleSize;
      descriptor.mode = SendMode::kMultiple;
      break;
    default: break;
  }
  return descriptor;
}

std::string DeviceInfo::SerialNumberHex() const {
  std::string text;
  char digits[3];
  for (uint8_t byte : serial_number) {
    std::snprintf(digits, sizeof digits, "%02X", byte);
    text += digits;
  }
  return text;
}

std::optional<DeviceInfo> ParseDeviceInfo(const uint8_t* data, size_t size) {
  if (size < kDeviceInfoSize) return std::nullopt;
  DeviceInfo info;
  info.model = data[0];
  info.firmware_minor = data[1];  // firmware_version is a LE u16: minor first, then major
  info.firmware_major = data[2];
  info.hardware = data[3];
  for (size_t i = 0; i < info.serial_number.size(); ++i) info.serial_number[i] = data[4 + i];
  return info;
}

std::vector<uint8_t> EncodeDeviceInfo(const DeviceInfo& info) {
  std::vector<uint8_t> bytes(kDeviceInfoSize);
  bytes[0] = info.model;
  bytes[1] = info.firmware_minor;
  bytes[2] = info.firmware_major;
  bytes[3] = info.hardware;
  for (size_t i = 0; i < info.serial_number.size(); ++i) bytes[4 + i] = info.serial_number[i];
  return bytes;
}

std::optional<DeviceHealth> ParseDeviceHealth(const uint8_t* data, size_t size) {
  if (size < kDeviceHealthSize || data[0] > 2) return std::nullopt;
  DeviceHealth health;
  health.status = static_cast<HealthStatus>(data[0]);
  health.error_code = ReadU16(data + 1);
  return health;
}

std::vector<uint8_t> EncodeDeviceHealth(const DeviceHealth& health) {
  std::vector<uint8_t> bytes = {static_cast<uint8_t>(health.status)};
  PutU16(&bytes, health.error_code);
  return bytes;
}

const char* HealthName(HealthStatus status) {
  switch (status) {
    case HealthStatus::kGood: return "good";
    case HealthStatus::kWarning: return "warning";
    case HealthStatus::kError: return "error";
  }
  return "unknown";
}

std::optional<SampleRate> ParseSampleRate(const uint8_t* data, size_t size) {
  if (size < kSampleRateSize) return std::nullopt;
  return SampleRate{ReadU16(data), ReadU16(data + 2)};
}

std::vector<uint8_t> EncodeSampleRate(const SampleRate& rate) {
  std::vector<uint8_t> bytes;
  PutU16(&bytes, rate.standard_us);
  PutU16(&bytes, rate.express_us);
  return bytes;
}

std::optional<uint32_t> ParseAccBoardFlag(const uint8_t* data, size_t size) {
  if (size < kAccBoardFlagSize) return std::nullopt;
  return ReadU32(data);
}

std::vector<uint8_t> EncodeAccBoardFlag(uint32_t flag) {
  std::vector<uint8_t> bytes;
  PutU32(&bytes, flag);
  return bytes;
}

void RequestParser::Reset() {
  state_ = State::kSync;
  current_ = Request();
  payload_size_ = 0;
  checksum_ = 0;
}

void RequestParser::Feed(const uint8_t* data, size_t size, std::vector<Request>* out) {
  for (size_t i = 0; i < size; ++i) {
    const uint8_t byte = data[i];
    switch (state_) {
      case State::kSync:
        if (byte == kRequestSync) {
          state_ = State::kCommand;
          checksum_ = byte;
        } else {
          ++skipped_bytes_;
        }
        break;
      case State::kCommand:
        current_ = Request();
        current_.command = byte;
        checksum_ ^= byte;
        if ((byte & 0x80) == 0) {
          out->push_back(current_);
          state_ = State::kSync;
        } else {
          state_ = State::kSize;
        }
        break;
      case State::kSize:
        checksum_ ^= byte;
        payload_size_ = byte;
        if (payload_size_ > kMaxRequestPayload) {
          ++bad_checksums_;
          skipped_bytes_ += 3;
          state_ = State::kSync;
        } else {
          state_ = payload_size_ == 0 ? State::kChecksum : State::kPayload;
        }
        break;
      case State::kPayload:
        checksum_ ^= byte;
        current_.payload.push_back(byte);
        if (current_.payload.size() == payload_size_) state_ = State::kChecksum;
        break;
      case State::kChecksum:
        if (byte == checksum_) {
          out->push_back(current_);
        } else {
          ++bad_checksums_;
        }
        state_ = State::kSync;
        break;
    }
  }
}

}  // namespace rplidar
}  // namespace slammtt
