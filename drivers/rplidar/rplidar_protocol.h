// The RPLIDAR A-series serial protocol (A2 here): request packets, reply descriptors and the
// single replies, for the host (driver) and the device (emulator) side. Pure: bytes in, values
// out; no I/O, no clock.
//
// Sources: Slamtec "RPLIDAR Interface Protocol and Application Notes" (v2.x) and the Slamtec
// rplidar_sdk, whose behaviour real devices were tested against: sdk/include/sl_lidar_cmd.h
// (command and answer codes, payload and reply layouts), sdk/include/sl_lidar_protocol.h
// (packet and descriptor layout), sdk/src/sl_lidarprotocol_codec.cpp (checksum, descriptor
// decoding). Our notes: ../shared/design/protocols/rplidar.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace slammtt {
namespace rplidar {

// Request byte 1 (sl_lidar_cmd.h). Commands with bit 7 set carry a payload.
enum Command : uint8_t {
  kStop = 0x25,            // no reply; wait >= 1 ms before the next request
  kReset = 0x40,           // no reply; the device reboots and prints a text banner
  kScan = 0x20,            // multi reply of 5-byte nodes, once rotation is stable
  kForceScan = 0x21,       // like kScan, without waiting for stable rotation
  kGetInfo = 0x50,         // single reply, 20 bytes
  kGetHealth = 0x52,       // single reply, 3 bytes
  kGetSampleRate = 0x59,   // single reply, 4 bytes (firmware >= 1.17)
  kExpressScan = 0x82,     // payload 5 bytes; multi reply of 84-byte capsules (fw >= 1.17)
  kGetLidarConf = 0x84,    // payload >= 4 bytes (fw >= 1.24); not used by our driver
  kSetMotorPwm = 0xF0,     // payload uint16 PWM; no reply (accessory board only)
  kGetAccBoardFlag = 0xFF, // payload uint32 0; single reply, 4 bytes
};

// Reply descriptor byte 6, the data type (sl_lidar_cmd.h "SL_LIDAR_ANS_TYPE_*").
enum AnswerType : uint8_t {
  kAnswerDeviceInfo = 0x04,
  kAnswerDeviceHealth = 0x06,
  kAnswerSampleRate = 0x15,
  kAnswerMeasurement = 0x81,          // standard scan node
  kAnswerMeasurementCapsuled = 0x82,  // legacy express capsule
  kAnswerAccBoardFlag = 0xFF,
};

inline constexpr uint8_t kRequestSync = 0xA5;
inline constexpr uint8_t kDescriptorSync1 = 0xA5;
inline constexpr uint8_t kDescriptorSync2 = 0x5A;
inline constexpr size_t kDescriptorSize = 7;
inline constexpr size_t kDeviceInfoSize = 20;
inline constexpr size_t kDeviceHealthSize = 3;
inline constexpr size_t kSampleRateSize = 4;
inline constexpr size_t kAccBoardFlagSize = 4;
inline constexpr size_t kStandardNodeSize = 5;
inline constexpr size_t kExpressCapsuleSize = 84;
// Default PWM the SDK applies to an A2 motor through the accessory board.
inline constexpr uint16_t kDefaultMotorPwm = 660;

// A request on the wire: "A5 cmd" without payload; "A5 cmd size payload checksum" with one,
// the checksum being the XOR of every byte before it (protocol document section "Request
// packets' format"; sl_lidarprotocol_codec.cpp onEncodeData).
std::vector<uint8_t> EncodeRequest(uint8_t command, const std::vector<uint8_t>& payload = {});

std::vector<uint8_t> StopRequest();
std::vector<uint8_t> ResetRequest();
std::vector<uint8_t> ScanRequest();
std::vector<uint8_t> ForceScanRequest();
// Legacy express scan: working mode 0, flags 0, parameter 0 (sl_lidar_payload_express_scan_t:
// u8 mode, u16 flags, u16 param).
std::vector<uint8_t> ExpressScanRequest();
std::vector<uint8_t> GetInfoRequest();
std::vector<uint8_t> GetHealthRequest();
std::vector<uint8_t> GetSampleRateRequest();
std::vector<uint8_t> SetMotorPwmRequest(uint16_t pwm);
std::vector<uint8_t> GetAccBoardFlagRequest();

// The 7-byte reply descriptor: A5 5A, a little-endian word whose low 30 bits are the reply
// length and top 2 bits the send mode, then the data type.
enum class SendMode : uint8_t { kSingle = 0, kMultiple = 1 };
struct ResponseDescriptor {
  uint32_t length = 0;  // bytes per reply (per node or capsule for multiple replies)
  SendMode mode = SendMode::kSingle;
  uint8_t data_type = 0;
};
// nullopt when the sync bytes are wrong or the mode is not 0 or 1.
std::optional<ResponseDescriptor> ParseDescriptor(const uint8_t* bytes);
std::vector<uint8_t> EncodeDescriptor(const ResponseDescriptor& descriptor);
// The descriptor every reply of a command starts with, for the emulator and for checks.
ResponseDescriptor DescriptorFor(uint8_t data_type);

// GET_INFO reply: model, firmware minor, firmware major, hardware, 16-byte serial number.
struct DeviceInfo {
  uint8_t model = 0;  // high nibble: model family (2 = A2, sl_lidar_driver.cpp)
  uint8_t firmware_major = 0;
  uint8_t firmware_minor = 0;
  uint8_t hardware = 0;
  std::array<uint8_t, 16> serial_number = {};
  // 32 upper-case hex digits, in wire order (how Slamtec's tools print it).
  std::string SerialNumberHex() const;
};
std::optional<DeviceInfo> ParseDeviceInfo(const uint8_t* data, size_t size);
std::vector<uint8_t> EncodeDeviceInfo(const DeviceInfo& info);

enum class HealthStatus : uint8_t { kGood = 0, kWarning = 1, kError = 2 };
struct DeviceHealth {
  HealthStatus status = HealthStatus::kGood;
  uint16_t error_code = 0;
};
// nullopt for a short reply or a status byte other than 0, 1, 2.
std::optional<DeviceHealth> ParseDeviceHealth(const uint8_t* data, size_t size);
std::vector<uint8_t> EncodeDeviceHealth(const DeviceHealth& health);
const char* HealthName(HealthStatus status);

// GET_SAMPLERATE reply: time per sample in microseconds, standard and express scan.
struct SampleRate {
  uint16_t standard_us = 0;
  uint16_t express_us = 0;
};
std::optional<SampleRate> ParseSampleRate(const uint8_t* data, size_t size);
std::vector<uint8_t> EncodeSampleRate(const SampleRate& rate);

// GET_ACC_BOARD_FLAG reply: bit 0 set = the motor takes SET_MOTOR_PWM.
inline constexpr uint32_t kAccBoardMotorPwmSupported = 0x1;
std::optional<uint32_t> ParseAccBoardFlag(const uint8_t* data, size_t size);
std::vector<uint8_t> EncodeAccBoardFlag(uint32_t flag);

// Device side: splits the host's byte stream into requests. Bytes before a 0xA5 are skipped;
// a payload request whose checksum is wrong, or whose size byte is over kMaxRequestPayload
// (no request of the protocol comes near it), is dropped and counted. Requests are complete packets: no timeout between bytes.
inline constexpr size_t kMaxRequestPayload = 64;
struct Request {
  uint8_t command = 0;
  std::vector<uint8_t> payload;
};
class RequestParser {
 public:
  // Appends every complete request in `data` to `out`.
  void Feed(const uint8_t* data, size_t size, std::vector<Request>* out);
  void Reset();
  int64_t skipped_bytes() const { return skipped_bytes_; }
  int64_t bad_checksums() const { return bad_checksums_; }

 private:
  enum class State { kSync, kCommand, kSize, kPayload, kChecksum };
  State state_ = State::kSync;
  Request current_;
  size_t payload_size_ = 0;
  uint8_t checksum_ = 0;
  int64_t skipped_bytes_ = 0;
  int64_t bad_checksums_ = 0;
};

}  // namespace rplidar
}  // namespace slammtt
