// What goes into and comes out of the P3-DX device session (p3dx_session.h), as plain structs:
// a velocity command in, odometry per SIP and the status of the driver and base out. The
// program's adapter turns them into and from VELOCITY_COMMAND, ODOMETRY and BASE_STATUS
// (p3dx_messages.h, whose fields these are, one for one); a test uses them as they are.
#pragma once

#include <cstdint>
#include <string>

#include "drivers/p3dx/p3dx_odometry.h"

namespace slammtt {

// A velocity set-point for the base (unicycle form), before the session clamps it to its limits.
struct BaseCommand {
  double linear_mps = 0.0;     // forward speed
  double angular_radps = 0.0;  // yaw rate, CCW positive
};

// The base's own odometry from one SIP.
struct BaseOdometry {
  int64_t utime = 0;     // host time the SIP's last byte was read [us since epoch]
  int64_t sequence = 0;  // 0, 1, 2, ... per session object
  P3dxOdometry reading;  // pose in the base's odometry frame and velocities (p3dx_odometry.h)
};

// Where the session is. kConnecting / kReconnecting: no link (before the first session reached
// kRunning / after). The others are P3dxSession::State's.
enum class BaseState {
  kConnecting,
  kReconnecting,
  kSyncing,
  kStoppingEarlierSession,
  kClosingEarlierSession,
  kOpening,
  kRunning,
  kStopped,
};
// "connecting", "reconnecting", "syncing", "stopping-earlier-session",
// "closing-earlier-session", "opening", "running", "stopped".
const char* BaseStateName(BaseState state);

// Who may drive the robot (docs/robot.md, "Who can drive the robot"): any command (kNone,
// command_authentication none), commands signed with the robot's key (kSigned), or none at all
// (kSignedWithoutKey: signed commands asked for, no key loaded).
enum class CommandAuthState { kNone, kSigned, kSignedWithoutKey };

// Why a command was refused (drivers/command_auth/command_signature.h, CommandVerdict).
enum class CommandRefusal { kUnauthenticated, kStale, kReplayed };

struct BaseStatus {
  int64_t utime = 0;  // host time of the report [us since epoch]
  bool connected = false;  // state kRunning
  BaseState state = BaseState::kConnecting;
  std::string endpoint;        // the configured port, then the open link's Describe()
  std::string robot_name;      // from the SYNC2 reply; "" before
  std::string robot_class;
  std::string robot_subclass;
  // From the last SIP; 0 and false before the first.
  double battery_v = 0.0;
  bool left_wheel_stall = false;
  bool right_wheel_stall = false;
  int bumpers = 0;  // bits 0-6 left bumpers, bits 8-14 right bumpers
  bool motors_enabled = false;
  bool command_timeout_stop = false;  // stopped because commands stopped arriving
  int64_t sips_received = 0;
  int64_t checksum_errors = 0;
  int64_t short_packets = 0;  // truncated packets and SIPs too short for their fields
  int64_t reconnects = 0;
  std::string last_error;  // "" until something went wrong
  CommandAuthState command_auth = CommandAuthState::kSigned;
  int64_t commands_accepted = 0;
  int64_t commands_unauthenticated = 0;  // no tag, a wrong tag, or no key to check it with
  int64_t commands_stale = 0;            // utime outside the freshness window
  int64_t commands_replayed = 0;         // counter not newer than its sender's last accepted
};

// Where the session sends what it measured. Called on the session's thread.
class P3dxSessionOutput {
 public:
  virtual ~P3dxSessionOutput() = default;
  virtual void OnBaseOdometry(const BaseOdometry& odometry) = 0;
  virtual void OnBaseStatus(const BaseStatus& status) = 0;
};

}  // namespace slammtt
