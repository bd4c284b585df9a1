#include "drivers/p3dx/p3dx_robot_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/angle.h"

namespace slammtt {
namespace {

constexpr double kPi = 3.14159265358979323846;

int Wrap(long value, long modulus) { return static_cast<int>(((value % modulus) + modulus) % modulus); }

}  // namespace

P3dxRobotModel::P3dxRobotModel(const P3dxRobotModelOptions& options)
    : options_(options),
      conversion_(P3dxConversionForSubclass(options.identity.subclass).value_or(P3dxConversion{})),
      random_(options.seed) {}

void P3dxRobotModel::Receive(const uint8_t* data, size_t size, int64_t now_us) {
  AdvanceTo(now_us);
  if (now_us_ < silent_until_us_) return;  // an unplugged line hears nothing either
  const int64_t errors_before = decoder_.counters().checksum_errors;
  decoder_.Feed(data, size);
  bad_packets_received_ += decoder_.counters().checksum_errors - errors_before;
  while (auto payload = decoder_.Next()) {
    const auto command = ParseP3dxClientCommand(*payload);
    if (!command) {
      ++bad_packets_received_;
      continue;
    }
    last_packet_us_ = now_us_;
    received_.push_back({now_us_, link_state_ == LinkState::kOpen, *command});
    Handle(*command, now_us_);
  }
}

void P3dxRobotModel::Handle(const P3dxClientCommand& command, int64_t now_us) {
  namespace cmd = p3dx_command;
  const uint8_t n = command.number;
  switch (link_state_) {
    case LinkState::kWaitSync0:
    case LinkState::kWaitSync1:
    case LinkState::kWaitSync2:
    case LinkState::kWaitOpen:
      if (n == cmd::kSync0) {
        Send(FrameP3dxPacket({cmd::kSync0}));
        link_state_ = LinkState::kWaitSync1;
      } else if (n == cmd::kSync1 && link_state_ == LinkState::kWaitSync1) {
        Send(FrameP3dxPacket({cmd::kSync1}));
        link_state_ = LinkState::kWaitSync2;
      } else if (n == cmd::kSync2 && link_state_ == LinkState::kWaitSync2) {
        Send(FrameP3dxPacket(EncodeP3dxRobotIdentity(options_.identity)));
        link_state_ = LinkState::kWaitOpen;
      } else if (n == cmd::kOpen && link_state_ == LinkState::kWaitOpen) {
        link_state_ = LinkState::kOpen;
        next_sip_us_ = now_us + options_.sip_cycle_ms * int64_t{1000};
      } else {
        link_state_ = LinkState::kWaitSync0;
      }
      return;
    case LinkState::kOpen:
      break;
  }
  switch (n) {
    case cmd::kClose:
      Stop();
      motors_enabled_ = false;
      link_state_ = LinkState::kWaitSync0;
      break;
    case cmd::kEnable:
      motors_enabled_ = command.value != 0;
      if (!motors_enabled_) Stop();
      break;
    case cmd::kVel: {
      const double angular_degps = (right_mmps_ - left_mmps_) / (conversion_.effective_track_m() * 1000.0) * 180.0 / kPi;
      SetMotion(command.value, angular_degps);
      break;
    }
    case cmd::kRvel:
      SetMotion(0.5 * (left_mmps_ + right_mmps_), command.value);
      break;
    case cmd::kVel2: {
      if (!motors_enabled_) break;
      int left = 0;
      int right = 0;
      SplitP3dxVel2(command.value, &left, &right);
      const double limit = options_.max_linear_mps * 1000.0;
      left_mmps_ = std::clamp(left * conversion_.vel2_divisor, -limit, limit);
      right_mmps_ = std::clamp(right * conversion_.vel2_divisor, -limit, limit);
      break;
    }
    case cmd::kStop:
    case cmd::kEstop:
      Stop();
      break;
    default:  // PULSE, OPEN again and everything we do not model: the watchdog is fed anyway
      break;
  }
}

void P3dxRobotModel::SetMotion(double linear_mmps, double angular_degps) {
  if (!motors_enabled_) return;
  const double v_limit = options_.max_linear_mps * 1000.0;
  const double v = std::clamp(linear_mmps, -v_limit, v_limit);
  const double w_degps = std::clamp(angular_degps, -options_.max_angular_degps, options_.max_angular_degps);
  const double half_track_mm = conversion_.effective_track_m() * 1000.0 / 2.0;
  const double w = w_degps * kPi / 180.0;
  left_mmps_ = v - w * half_track_mm;
  right_mmps_ = v + w * half_track_mm;
}

void P3dxRobotModel::Stop() {
  left_mmps_ = 0.0;
  right_mmps_ = 0.0;
}

void P3dxRobotModel::Integrate(int64_t to_us) {
  if (to_us <= now_us_) return;
  const double dt = (to_us - now_us_) * 1e-6;
  now_us_ = to_us;
  if (!moving()) return;
  const double v = 0.5 * (left_mmps_ + right_mmps_);
  const double w = (right_mmps_ - left_mmps_) / (conversion_.effective_track_m() * 1000.0);
  if (std::abs(w) < 1e-9) {
    x_mm_ += v * dt * std::cos(heading_rad_);
    y_mm_ += v * dt * std::sin(heading_rad_);
  } else {
    // Exact arc for constant wheel speeds.
    const double next_heading = heading_rad_ + w * dt;
    x_mm_ += v / w * (std::sin(next_heading) - std::sin(heading_rad_));
    y_mm_ -= v / w * (std::cos(next_heading) - std::cos(heading_rad_));
    heading_rad_ = WrapAngle(next_heading);
  }
}

void P3dxRobotModel::AdvanceTo(int64_t now_us) {
  if (now_us < now_us_) return;
  const int64_t watchdog_us = options_.watchdog_ms * int64_t{1000};
  for (;;) {
    const bool open = link_state_ == LinkState::kOpen;
    int64_t event = now_us;
    if (open) event = std::min(event, next_sip_us_);
    if (open && moving()) event = std::min(event, last_packet_us_ + watchdog_us);
    Integrate(event);
    if (open && moving() && now_us_ >= last_packet_us_ + watchdog_us) {
      Stop();
      ++watchdog_stops_;
    }
    if (open && now_us_ >= next_sip_us_) {
      if (now_us_ >= silent_until_us_ && now_us_ >= muted_until_us_) SendSip();
      next_sip_us_ += options_.sip_cycle_ms * int64_t{1000};
    }
    if (now_us_ >= now_us) break;
  }
}

int64_t P3dxRobotModel::NextEventUs() const {
  int64_t next = std::numeric_limits<int64_t>::max();
  if (link_state_ == LinkState::kOpen) {
    next = std::min(next, next_sip_us_);
    if (moving()) next = std::min<int64_t>(next, last_packet_us_ + options_.watchdog_ms * int64_t{1000});
  }
  if (silent_until_us_ > now_us_) next = std::min(next, silent_until_us_);
  if (muted_until_us_ > now_us_) next = std::min(next, muted_until_us_);
  return next;
}

void P3dxRobotModel::SendSip() {
  P3dxStandardSip sip;
  sip.moving = moving();
  sip.x_pos = static_cast<uint16_t>(Wrap(std::lround(x_mm_ / conversion_.dist_conv_mm), 32768));
  sip.y_pos = static_cast<uint16_t>(Wrap(std::lround(y_mm_ / conversion_.dist_conv_mm), 32768));
  int th = Wrap(std::lround(heading_rad_ / conversion_.angle_conv_rad), 4096);
  if (options_.signed_thpos && th > 2047) th -= 4096;
  sip.th_pos = static_cast<int16_t>(th);
  sip.left_vel = static_cast<int16_t>(std::lround(left_mmps_ / conversion_.vel_conv));
  sip.right_vel = static_cast<int16_t>(std::lround(right_mmps_ / conversion_.vel_conv));
  const long decivolts = std::clamp(std::lround(options_.battery_v * 10.0), 0L, 255L);
  sip.battery_decivolts = static_cast<uint8_t>(decivolts);
  sip.stall_and_bumpers = stall_and_bumpers_;
  sip.control = sip.th_pos;
  sip.flags = motors_enabled_ ? 0x0001 : 0x0000;
  for (int i = 0; i < options_.sonar_count; ++i) {
    sip.sonars.push_back({static_cast<uint8_t>(i), static_cast<uint16_t>(1000 + 100 * i)});
  }
  if (options_.extended_sip) {
    sip.io = P3dxSipIo{};
    sip.battery_decivolts_x10 = static_cast<uint16_t>(std::lround(options_.battery_v * 10.0));
    sip.charge_state = 0;
    const double w_degps = (right_mmps_ - left_mmps_) / (conversion_.effective_track_m() * 1000.0) * 180.0 / kPi;
    sip.rot_vel_decideg_per_s = static_cast<int16_t>(std::lround(w_degps * 10.0));
    sip.fault_flags = 0;
  }
  std::vector<uint8_t> payload = EncodeP3dxStandardSip(sip);
  if (short_sips_ > 0) {
    --short_sips_;
    payload.resize(12);
  }
  ++sips_sent_;
  Send(FrameP3dxPacket(payload));
}

void P3dxRobotModel::Send(std::vector<uint8_t> packet) {
  if (now_us_ < muted_until_us_) return;
  if (corrupt_checksums_ > 0) {
    --corrupt_checksums_;
    packet.back() ^= 0x01;
  }
  if (truncate_packets_ > 0) {
    --truncate_packets_;
    packet.resize(packet.size() / 2);
  }
  if (drop_bytes_ > 0 && packet.size() > 6) {
    // Keep header, count and id; lose bytes from the middle, never the whole packet.
    const int removable = static_cast<int>(packet.size()) - 6;
    const int removed = std::min(drop_bytes_, removable);
    packet.erase(packet.begin() + 4, packet.begin() + 4 + removed);
    drop_bytes_ -= removed;
  }
  output_.insert(output_.end(), packet.begin(), packet.end());
}

std::vector<uint8_t> P3dxRobotModel::TakeOutput() {
  std::vector<uint8_t> bytes(output_.begin(), output_.end());
  output_.clear();
  return bytes;
}

void P3dxRobotModel::StartConnected(double linear_mps, double angular_radps, int64_t now_us) {
  AdvanceTo(now_us);
  link_state_ = LinkState::kOpen;
  motors_enabled_ = true;
  SetMotion(linear_mps * 1000.0, angular_radps * 180.0 / kPi);
  next_sip_us_ = now_us_ + options_.sip_cycle_ms * int64_t{1000};
  last_packet_us_ = now_us_;
}

void P3dxRobotModel::HostDisconnected() {
  decoder_.Reset();
  output_.clear();
  if (link_state_ != LinkState::kOpen) link_state_ = LinkState::kWaitSync0;
}

void P3dxRobotModel::InjectGarbage(int bytes, bool allow_header_byte) {
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < bytes;) {
    const uint8_t value = static_cast<uint8_t>(byte(random_));
    if (!allow_header_byte && value == kP3dxHeader0) continue;
    output_.push_back(value);
    ++i;
  }
}

void P3dxRobotModel::CorruptNextChecksums(int packets) { corrupt_checksums_ += packets; }
void P3dxRobotModel::DropNextBytes(int bytes) { drop_bytes_ += bytes; }
void P3dxRobotModel::SendShortSips(int packets) { short_sips_ += packets; }
void P3dxRobotModel::TruncateNextPackets(int packets) { truncate_packets_ += packets; }

void P3dxRobotModel::SilenceFor(int64_t duration_us, int64_t now_us) {
  AdvanceTo(now_us);
  silent_until_us_ = now_us_ + duration_us;
}

void P3dxRobotModel::MuteFor(int64_t duration_us, int64_t now_us) {
  AdvanceTo(now_us);
  muted_until_us_ = now_us_ + duration_us;
}

void P3dxRobotModel::SetBumpers(int left_bits, int right_bits) {
  stall_and_bumpers_ = static_cast<uint16_t>((stall_and_bumpers_ & 0x0101) | ((left_bits & 0x7F) << 1) |
                                             ((right_bits & 0x7F) << 9));
}

void P3dxRobotModel::SetWheelStall(bool left, bool right) {
  stall_and_bumpers_ = static_cast<uint16_t>((stall_and_bumpers_ & ~0x0101) | (left ? 0x0001 : 0) |
                                             (right ? 0x0100 : 0));
}

}  // namespace slammtt
