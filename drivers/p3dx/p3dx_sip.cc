#include "drivers/p3dx/p3dx_sip.h"

#include <algorithm>
#include <cctype>

namespace slammtt {
namespace {

// Little-endian reader that refuses to read past the end.
class PayloadReader {
 public:
  explicit PayloadReader(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}
  size_t remaining() const { return bytes_.size() - position_; }
  uint8_t U8() { return bytes_[position_++]; }
  uint16_t U16() {
    const uint16_t value = static_cast<uint16_t>(bytes_[position_] | (bytes_[position_ + 1] << 8));
    position_ += 2;
    return value;
  }
  int16_t S16() { return static_cast<int16_t>(U16()); }

 private:
  const std::vector<uint8_t>& bytes_;
  size_t position_ = 0;
};

void PutU16(std::vector<uint8_t>* out, uint16_t value) {
  out->push_back(static_cast<uint8_t>(value & 0xFF));
  out->push_back(static_cast<uint8_t>(value >> 8));
}
void PutS16(std::vector<uint8_t>* out, int16_t value) { PutU16(out, static_cast<uint16_t>(value)); }

// Bytes of the mandatory part: type 1, XPOS..R VEL 10, BATTERY 1, STALL 2, CONTROL 2, FLAGS 2,
// COMPASS 1, SONAR COUNT 1.
constexpr size_t kMandatoryBytes = 20;

}  // namespace

P3dxSipParse ParseP3dxStandardSip(const std::vector<uint8_t>& payload) {
  P3dxSipParse result;
  if (payload.empty() || !IsP3dxSipType(payload[0])) return result;
  if (payload.size() < kMandatoryBytes) {
    result.status = P3dxSipStatus::kShort;
    return result;
  }
  PayloadReader in(payload);
  P3dxStandardSip& sip = result.sip;
  sip.moving = in.U8() == kP3dxSipMoving;
  sip.x_pos = in.U16() & 0x7FFF;
  sip.y_pos = in.U16() & 0x7FFF;
  sip.th_pos = in.S16();
  sip.left_vel = in.S16();
  sip.right_vel = in.S16();
  sip.battery_decivolts = in.U8();
  sip.stall_and_bumpers = in.U16();
  sip.control = in.S16();
  sip.flags = in.U16();
  sip.compass = in.U8();
  const size_t sonar_count = in.U8();
  if (in.remaining() < 3 * sonar_count) {
    result.status = P3dxSipStatus::kShort;
    return result;
  }
  sip.sonars.resize(sonar_count);
  for (P3dxSonarReading& sonar : sip.sonars) {
    sonar.number = in.U8();
    sonar.range = in.U16();
  }
  // Optional groups, in order; the first incomplete one ends the packet for us.
  if (in.remaining() >= 5) {
    P3dxSipIo io;
    io.grip_state = in.U8();
    io.analog_port = in.U8();
    io.analog = in.U8();
    io.digital_in = in.U8();
    io.digital_out = in.U8();
    sip.io = io;
    if (in.remaining() >= 2) {
      sip.battery_decivolts_x10 = in.U16();
      if (in.remaining() >= 1) {
        sip.charge_state = in.U8();
        if (in.remaining() >= 2) {
          sip.rot_vel_decideg_per_s = in.S16();
          if (in.remaining() >= 2) sip.fault_flags = in.U16();
        }
      }
    }
  }
  result.status = P3dxSipStatus::kOk;
  return result;
}

std::vector<uint8_t> EncodeP3dxStandardSip(const P3dxStandardSip& sip) {
  std::vector<uint8_t> out;
  out.push_back(sip.moving ? kP3dxSipMoving : kP3dxSipStopped);
  PutU16(&out, sip.x_pos & 0x7FFF);
  PutU16(&out, sip.y_pos & 0x7FFF);
  PutS16(&out, sip.th_pos);
  PutS16(&out, sip.left_vel);
  PutS16(&out, sip.right_vel);
  out.push_back(sip.battery_decivolts);
  PutU16(&out, sip.stall_and_bumpers);
  PutS16(&out, sip.control);
  PutU16(&out, sip.flags);
  out.push_back(sip.compass);
  const size_t sonar_count = std::min<size_t>(sip.sonars.size(), 60);
  out.push_back(static_cast<uint8_t>(sonar_count));
  for (size_t i = 0; i < sonar_count; ++i) {
    out.push_back(sip.sonars[i].number);
    PutU16(&out, sip.sonars[i].range);
  }
  int last_group = 0;
  if (sip.io) last_group = 1;
  if (sip.battery_decivolts_x10) last_group = 2;
  if (sip.charge_state) last_group = 3;
  if (sip.rot_vel_decideg_per_s) last_group = 4;
  if (sip.fault_flags) last_group = 5;
  if (last_group >= 1) {
    const P3dxSipIo io = sip.io.value_or(P3dxSipIo{});
    out.insert(out.end(), {io.grip_state, io.analog_port, io.analog, io.digital_in, io.digital_out});
  }
  if (last_group >= 2) PutU16(&out, sip.battery_decivolts_x10.value_or(0));
  if (last_group >= 3) out.push_back(sip.charge_state.value_or(0));
  if (last_group >= 4) PutS16(&out, sip.rot_vel_decideg_per_s.value_or(0));
  if (last_group >= 5) PutU16(&out, sip.fault_flags.value_or(0));
  return out;
}

std::optional<P3dxRobotIdentity> ParseP3dxRobotIdentity(const std::vector<uint8_t>& payload) {
  if (payload.empty() || payload[0] != kP3dxNamePacket) return std::nullopt;
  P3dxRobotIdentity identity;
  std::string* fields[3] = {&identity.name, &identity.robot_class, &identity.subclass};
  size_t position = 1;
  for (std::string* field : fields) {
    while (position < payload.size() && payload[position] != 0) {
      field->push_back(static_cast<char>(payload[position++]));
    }
    ++position;  // the terminator (or one past the end)
  }
  for (char& c : identity.subclass) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return identity;
}

std::vector<uint8_t> EncodeP3dxRobotIdentity(const P3dxRobotIdentity& identity) {
  std::vector<uint8_t> out = {kP3dxNamePacket};
  for (const std::string* field : {&identity.name, &identity.robot_class, &identity.subclass}) {
    out.insert(out.end(), field->begin(), field->end());
    out.push_back(0);
  }
  return out;
}

}  // namespace slammtt
