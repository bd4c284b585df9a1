// The device side of a P3-DX for the emulator and the tests: the ARCOS connection state machine,
// a differential-drive base that integrates the velocities it is commanded, the firmware
// watchdog, and fault injection. Pure: bytes in, bytes out, time given by the caller (no clock,
// no I/O, seeded randomness), so the same calls always give the same bytes.
//
// Behaviour (Pioneer 3 Operations Manual 2006, ARCOS chapter; ../shared/design/protocols/p3dx.md):
//  - not connected: SYNC0, SYNC1 are echoed in order, SYNC2 is answered with the name packet;
//    a SYNC out of order restarts the sequence; everything else is ignored;
//  - after the name packet, OPEN starts the server: a standard SIP every SIP cycle (100 ms);
//  - connected: PULSE (= SYNC0) only feeds the watchdog, ENABLE, VEL, RVEL, VEL2, STOP, ESTOP set
//    the motion, CLOSE stops the robot and ends the session (no more SIPs); any other valid
//    command (HOSTBAUD included: the emulated line has no rate) only feeds the watchdog;
//  - the watchdog stops the robot when no valid packet came for `watchdog_ms` (ARCOS default 2 s);
//    motion resumes only with a new motion command.
// VEL/RVEL become wheel speeds through the effective track 2 / DiffConvFactor, as the host's
// odometry assumes; SIP values are the pose in counter units (XPOS = x_mm / DistConvFactor).
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "drivers/p3dx/p3dx_commands.h"
#include "drivers/p3dx/p3dx_odometry.h"
#include "drivers/p3dx/p3dx_packet.h"
#include "drivers/p3dx/p3dx_sip.h"

namespace slammtt {

struct P3dxRobotModelOptions {
  P3dxRobotIdentity identity{"slammtt-emulator", "Pioneer", "p3dx"};
  int sip_cycle_ms = 100;
  int watchdog_ms = 2000;
  double max_linear_mps = 1.5;        // the firmware's own limits
  double max_angular_degps = 300.0;
  double battery_v = 12.5;
  bool extended_sip = true;           // send BATTERYX10, CHARGESTATE, ROTVEL, FAULTFLAGS
  bool signed_thpos = false;          // THPOS in [-2048, 2047] instead of [0, 4095]
  int sonar_count = 0;                // sonar readings per SIP (fixed fake ranges)
  uint32_t seed = 1;                  // garbage bytes
};

// One valid command the robot received, for tests to inspect.
struct P3dxReceivedCommand {
  int64_t time_us = 0;
  bool connected = false;  // the session was open when it arrived (PULSE vs SYNC0 and so on)
  P3dxClientCommand command;
};

class P3dxRobotModel {
 public:
  enum class LinkState { kWaitSync0, kWaitSync1, kWaitSync2, kWaitOpen, kOpen };

  explicit P3dxRobotModel(const P3dxRobotModelOptions& options = P3dxRobotModelOptions{});

  // Bytes from the host arriving at `now_us` (the model first advances to `now_us`).
  void Receive(const uint8_t* data, size_t size, int64_t now_us);
  // Advances motion, SIP schedule and watchdog to `now_us` (never backwards).
  void AdvanceTo(int64_t now_us);
  // Bytes for the host produced so far; the queue is emptied.
  std::vector<uint8_t> TakeOutput();
  // The next time something happens by itself (a SIP, the watchdog, the end of a silence), or
  // INT64_MAX.
  int64_t NextEventUs() const;

  // A session that was open before the host came (a host that crashed): SIPs run, the robot
  // moves at the given speeds, motors enabled.
  void StartConnected(double linear_mps, double angular_radps, int64_t now_us);
  // The host side went away (cable, bridge): decoder state is dropped, the session is not (the
  // firmware does not know; its watchdog will stop the robot).
  void HostDisconnected();

  // Fault injection: each applies to what the robot sends from now on.
  // Random bytes at once; without 0xFA they can never start a packet, so a test can demand that
  // not one of them is lost in a false frame.
  void InjectGarbage(int bytes, bool allow_header_byte = true);
  void CorruptNextChecksums(int packets);  // flip a checksum bit of the next packets
  void DropNextBytes(int bytes);           // drop bytes from the middle of the next packet(s)
  void SendShortSips(int packets);         // valid frame, SIP cut after 12 payload bytes
  void TruncateNextPackets(int packets);   // cut the frame in half, the rest never comes
  void SilenceFor(int64_t duration_us, int64_t now_us);  // no output, input ignored
  // No output (no SIP, no reply) while every packet is still heard and carried out: a robot
  // whose transmit line failed. Its watchdog is fed by whatever the host sends.
  void MuteFor(int64_t duration_us, int64_t now_us);
  void SetBumpers(int left_bits, int right_bits);        // 7 bits each
  void SetWheelStall(bool left, bool right);

  // Inspection.
  bool connected() const { return link_state_ == LinkState::kOpen; }
  bool motors_enabled() const { return motors_enabled_; }
  double left_wheel_mmps() const { return left_mmps_; }
  double right_wheel_mmps() const { return right_mmps_; }
  bool moving() const { return left_mmps_ != 0.0 || right_mmps_ != 0.0; }
  double x_mm() const { return x_mm_; }
  double y_mm() const { return y_mm_; }
  double heading_rad() const { return heading_rad_; }
  const std::vector<P3dxReceivedCommand>& received() const { return received_; }
  int64_t sips_sent() const { return sips_sent_; }
  int64_t watchdog_stops() const { return watchdog_stops_; }
  int64_t bad_packets_received() const { return bad_packets_received_; }
  const P3dxConversion& conversion() const { return conversion_; }

 private:
  void Handle(const P3dxClientCommand& command, int64_t now_us);
  void Integrate(int64_t to_us);
  void SendSip();
  void Send(std::vector<uint8_t> packet);
  void SetMotion(double linear_mmps, double angular_degps);
  void Stop();

  P3dxRobotModelOptions options_;
  P3dxConversion conversion_;
  LinkState link_state_ = LinkState::kWaitSync0;
  P3dxPacketDecoder decoder_;
  std::deque<uint8_t> output_;
  std::mt19937 random_;

  int64_t now_us_ = 0;
  int64_t next_sip_us_ = 0;
  int64_t last_packet_us_ = 0;
  int64_t silent_until_us_ = 0;
  int64_t muted_until_us_ = 0;

  bool motors_enabled_ = false;
  double left_mmps_ = 0.0;
  double right_mmps_ = 0.0;
  double x_mm_ = 0.0;
  double y_mm_ = 0.0;
  double heading_rad_ = 0.0;
  uint16_t stall_and_bumpers_ = 0;

  int corrupt_checksums_ = 0;
  int drop_bytes_ = 0;
  int short_sips_ = 0;
  int truncate_packets_ = 0;

  std::vector<P3dxReceivedCommand> received_;
  int64_t sips_sent_ = 0;
  int64_t watchdog_stops_ = 0;
  int64_t bad_packets_received_ = 0;
};

}  // namespace slammtt
