// The P3-DX device session: one session with the robot's microcontroller over a ByteStream,
// from the SYNC handshake to CLOSE, and what it reports (p3dx_session_output.h: BaseOdometry per
// SIP, BaseStatus). Pure: the link factory, the clock, the output and the log are given; it
// knows no message and no bus (the program's adapter, p3dx_driver.h, publishes ODOMETRY and
// BASE_STATUS and checks who sent a VELOCITY_COMMAND). Single-threaded: the owner calls Poll()
// in its loop and hands commands to AcceptCommand() or RefuseCommand(). A process waits
// in one poll() on the link's LinkPollDescriptor(), the bus and its shutdown descriptor for at
// most MillisecondsUntilDue(), then calls Poll(0); a test may instead let Poll() wait in the
// link's Read. The link factory and the clock are injected, so tests run the whole session
// against an emulated robot in simulated time.
//
// Session (Pioneer 3 Operations Manual 2006, ARCOS "Client-Server Communication"; ARIA
// ArRobot::asyncConnectHandler; ../shared/design/protocols/p3dx.md):
//  1. open the link, flush it, send SYNC0; SYNC0 and SYNC1 must come back as echoes, SYNC2's
//     reply is the name packet (name, class, subclass: the subclass picks DistConvFactor).
//     A SYNC without reply is re-sent every sync_reply_timeout_s; after sync_attempts the link
//     is reopened. A wrong reply restarts at SYNC0. Every SYNC0 goes out behind VEL2 0: a
//     robot still in a session (one that went quiet but still hears) takes SYNC0 as a
//     keep-alive and would keep driving; a robot waiting for SYNC0 ignores the VEL2.
//  2. A robot still connected to an earlier client answers SYNC with SIPs. If it is moving
//     (0x33) it takes our SYNC0 as a keep-alive and keeps driving, so we stop it first: VEL2 0,
//     and ESTOP if it still moves 1 s later. Once a SIP says stopped (0x32) we send CLOSE, wait
//     until its SIPs stop, and start again at SYNC0.
//  3. OPEN, then ENABLE 1 (motors on). The first SIP makes the session "running".
//  4. Running: every SIP gives one BaseOdometry (utime = host time of the SIP's arrival, i.e. when
//     its last byte was read; the firmware's own sample time is not in the SIP) and updates
//     the BaseStatus. A BaseCommand is clamped and sent as VEL [mm/s] + RVEL [deg/s] (RVEL
//     has 1 deg/s steps; VEL2 would only have 20 mm/s per wheel); a value that did not change
//     is repeated every pulse_interval_s, otherwise PULSE is sent then, so the firmware
//     watchdog never starves and a lost VEL is repaired.
//  5. No valid command for command_timeout_s while moving: VEL 0 + RVEL 0 (the robot stops
//     with its configured deceleration) and command_timeout_stop in the status until the next
//     command. A command with a non-finite value is skipped and counted.
//  6. No valid SIP for sip_timeout_s, or a LinkError: the link is lost: VEL2 0 is sent if the
//     link still takes it, the loss reported, the link closed and reopened after a backoff
//     (0.5 s doubling to 8 s) with the full handshake; the odometry stays continuous across the
//     gap (P3dxOdometryIntegrator::Reanchor).
//  7. Shutdown(): VEL 0 + RVEL 0, then CLOSE (which also stops the robot and ends its SIPs).
// Who may drive it: the adapter checks each VELOCITY_COMMAND from the bus (a signature with the
// robot's key, command_signature.h, unless options.command_authentication is kNone) and hands the
// session the command (AcceptCommand) or the refusal (RefuseCommand); a refused command never
// moves the robot, and is counted by reason in the status and reported the 1st, 10th, 100th, ...
// time.
// Bad checksums, bad byte counts, truncated packets and SIPs too short for their fields are
// skipped and counted; none of them ever gives odometry.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/common/driver_log.h"
#include "drivers/common/reconnect_backoff.h"
#include "drivers/p3dx/p3dx_driver_options.h"
#include "drivers/p3dx/p3dx_odometry.h"
#include "drivers/p3dx/p3dx_packet.h"
#include "drivers/p3dx/p3dx_session_output.h"
#include "drivers/p3dx/p3dx_sip.h"

namespace slammtt {

// Opens the link: OpenByteStream in the process, an emulated robot in tests.
using ByteStreamFactory =
    std::function<std::unique_ptr<ByteStream>(const std::string& endpoint, int baud)>;

class P3dxSession {
 public:
  enum class State {
    kDisconnected,  // no link; the next attempt is due at next_attempt_us_
    kSyncing,       // SYNC0/1/2 handshake
    kStoppingStale, // a connected robot was moving: stopping it before CLOSE
    kClosingStale,  // CLOSE sent to the earlier session; waiting for its SIPs to stop
    kOpening,       // OPEN and ENABLE sent, waiting for the first SIP
    kRunning,
    kStopped,       // after Shutdown()
  };

  // `clock`, `output` and `log` (may be null: no lines) outlive the session. Throws
  // std::invalid_argument, one line naming the key, for options CheckP3dxDriverOptions refuses.
  P3dxSession(const P3dxDriverOptions& options, ByteStreamFactory factory, DriverClock* clock,
              P3dxSessionOutput* output, DriverLog* log);
  // Shutdown() unless it ran.
  ~P3dxSession();
  P3dxSession(const P3dxSession&) = delete;
  P3dxSession& operator=(const P3dxSession&) = delete;

  // Does what is due: opens the link when its backoff expired, runs the timers, reads the link
  // for at most `max_wait_ms` (less when a timer is due sooner; 0 reads only what is there) and
  // handles what came. Never throws for link trouble (that is reported and retried). Returns
  // without waiting when there is no link.
  void Poll(int max_wait_ms);
  // The adapter holds the robot's key (with command_authentication kSigned): the status says
  // signed commands are checked, instead of "every command refused".
  void SetCommandKeyLoaded() { command_key_loaded_ = true; }
  // A command that passed the adapter's check: counted as accepted, then HandleCommand().
  // Nothing after Shutdown().
  void AcceptCommand(const BaseCommand& command);
  // A command the adapter's check refused: counted by `reason` and reported ("VELOCITY_COMMAND
  // refused: <why> (N refused so far, ...)") the 1st, 10th, 100th, ... time. Nothing after
  // Shutdown().
  void RefuseCommand(CommandRefusal reason, const std::string& why);
  // A command from someone allowed to drive the robot (sent at once when connected); a
  // non-finite value is skipped and counted.
  void HandleCommand(const BaseCommand& command);
  // Stops the robot and ends the session (VEL 0, RVEL 0, CLOSE); reports the final status.
  void Shutdown();

  // Milliseconds until Poll() has something to do that no input announces: the next link
  // attempt, SYNC re-send, SIP timeout, PULSE, command timeout, status or the deadline of a
  // partial packet. 0 when one is due now (and after Shutdown(), when Poll() does nothing).
  int MillisecondsUntilDue() const;
  // The open link's ByteStream::PollDescriptor(): -1 without a link or when the link has none.
  int LinkPollDescriptor() const { return link_ ? link_->PollDescriptor() : -1; }
  bool link_open() const { return link_ != nullptr; }
  State state() const { return state_; }
  static const char* StateName(State state);
  // The status as it would be reported now.
  BaseStatus Status() const;

  int64_t commands_skipped() const { return commands_skipped_; }
  int64_t commands_refused() const {
    return commands_unauthenticated_ + commands_stale_ + commands_replayed_;
  }
  const P3dxDecoderCounters& decoder_counters() const { return decoder_.counters(); }

 private:
  void TryOpen(int64_t now_us);
  void LinkLost(const std::string& reason);
  void SetState(State state);
  void StartSync();
  void SendSync(int index);
  bool Send(const std::vector<uint8_t>& packet);  // false when the link was lost
  void RunTimers(int64_t now_us);
  void ReadLink(int wait_ms);
  void HandlePacket(const std::vector<uint8_t>& payload, int64_t arrival_utime);
  void HandleSyncReply(const std::vector<uint8_t>& payload);
  void HandleStaleSip(const P3dxStandardSip& sip);
  void HandleSip(const P3dxStandardSip& sip, int64_t arrival_utime);
  void SendVelocity();
  void PublishStatus();
  int64_t NextTimerUs() const;
  // Lines for the people running the driver (driver_log.h).
  DriverLogLine LogDebug() const { return DriverLogLine(log_, DriverLogLevel::kDebug); }
  DriverLogLine LogInfo() const { return DriverLogLine(log_, DriverLogLevel::kInfo); }
  DriverLogLine LogWarning() const { return DriverLogLine(log_, DriverLogLevel::kWarning); }

  P3dxDriverOptions options_;
  ByteStreamFactory factory_;
  DriverClock* clock_;
  P3dxSessionOutput* output_;
  DriverLog* log_;

  std::unique_ptr<ByteStream> link_;
  std::string endpoint_description_;
  State state_ = State::kDisconnected;
  ReconnectBackoff backoff_;
  int64_t next_attempt_us_ = 0;
  bool had_session_ = false;     // a session reached kRunning before: the next one is a reconnect
  bool shutting_down_ = false;  // Shutdown() runs: a lost link is not reopened

  P3dxPacketDecoder decoder_;
  int64_t last_byte_us_ = 0;

  int sync_index_ = 0;        // the SYNC whose reply we wait for
  int sync_attempts_ = 0;     // unanswered sends of it
  int64_t sync_sent_us_ = 0;
  int64_t stale_since_us_ = 0;     // kStoppingStale: first moving SIP
  bool stale_estop_sent_ = false;
  int64_t close_sent_us_ = 0;      // kClosingStale
  int64_t last_stale_sip_us_ = 0;
  int64_t opened_us_ = 0;          // kOpening / kRunning: OPEN sent, or last valid SIP

  P3dxRobotIdentity identity_;
  P3dxOdometryIntegrator odometry_;
  int64_t odometry_sequence_ = 0;
  int64_t last_sip_us_ = 0;

  // Velocity: what was asked (clamped, in robot units) and what was last sent.
  bool have_command_ = false;
  int64_t last_command_us_ = 0;
  int target_vel_mmps_ = 0;
  int target_rvel_degps_ = 0;
  bool sent_once_ = false;
  int sent_vel_mmps_ = 0;
  int sent_rvel_degps_ = 0;
  int64_t last_write_us_ = 0;
  bool command_timeout_stop_ = false;
  int64_t commands_skipped_ = 0;

  // Who drives the robot.
  bool command_key_loaded_ = false;
  int64_t commands_accepted_ = 0;
  int64_t commands_unauthenticated_ = 0;
  int64_t commands_stale_ = 0;
  int64_t commands_replayed_ = 0;

  // Status.
  P3dxStandardSip last_sip_;
  bool have_sip_ = false;
  int64_t sips_received_ = 0;
  int64_t short_sips_ = 0;
  int64_t other_packets_ = 0;
  int64_t reconnects_ = 0;
  std::string last_error_;
  int64_t next_status_us_ = 0;
};

}  // namespace slammtt
