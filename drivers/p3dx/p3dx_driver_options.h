// Options of the P3-DX base driver: the `p3dx:` section of the stack configuration, then the
// command line (which wins; both read by p3dx_driver_config.h). Pure: the device session
// (p3dx_session.h) checks them in its constructor (CheckP3dxDriverOptions).
//
// VisitP3dxDriverOptions lists every option once (key, range, doc; common/options_schema.h):
// the reader of the `p3dx:` section, CheckP3dxDriverOptions and the table of docs/p3dx.md
// ("Options", printed by slammtt-p3dx --options-table) come from it.
#pragma once

#include <string>

#include "common/options_schema.h"

namespace slammtt {

struct P3dxDriverOptions {
  // Link: a serial port (opened through libserialport, 8N1) or "tcp://HOST:PORT".
  std::string port = "/dev/ttyUSB0";
  int baud = 9600;  // the ARCOS host port's default rate

  // Velocity limits applied to VELOCITY_COMMAND before it goes to the robot.
  double max_linear_mps = 0.5;
  double max_angular_radps = 1.0;
  // Stop the robot when no VELOCITY_COMMAND came for this long.
  double command_timeout_s = 0.5;
  // Send PULSE (or repeat the current VEL/RVEL) when nothing was sent for this long, so the
  // firmware watchdog (2 s by default) never fires while we are connected.
  double pulse_interval_s = 0.5;

  // Link supervision.
  double sync_reply_timeout_s = 0.5;  // re-send a SYNC whose reply has not come
  int sync_attempts = 8;              // unanswered SYNCs before the link is reopened
  double sip_timeout_s = 1.0;         // no valid SIP for this long: the link is lost
  double reconnect_initial_s = 0.5;   // backoff before reopening: doubles up to the maximum
  double reconnect_max_s = 8.0;

  // "" takes the conversion factors from the subclass in the robot's SYNC2 reply; "p3dx" or
  // "p3dx-sh" forces them (a robot whose firmware reports something else).
  std::string subclass;
  bool enable_motors = true;      // send ENABLE 1 after OPEN
  double status_period_s = 1.0;   // BASE_STATUS period (also sent on every state change)

  // Who may drive the robot (drivers/command_auth/command_signature.h; docs/robot.md, "Who can
  // drive the robot"). kSigned: only a VELOCITY_COMMAND signed with the key in command_key_file;
  // without a key file every command is refused (and counted). kNone: any VELOCITY_COMMAND
  // moves the robot; allowed only on a bus that keeps its packets on the host (ttl=0).
  enum class CommandAuthentication { kSigned, kNone };
  CommandAuthentication command_authentication = CommandAuthentication::kSigned;
  std::string command_key_file;     // empty: no key
  double command_max_age_s = 1.0;   // freshness window of a signed command, either way
};

// "hmac-sha256" or "none", the configuration's spelling.
const char* CommandAuthenticationName(P3dxDriverOptions::CommandAuthentication mode);

// The options schema of the driver, in the order of P3dxDriverOptions. Keys are the field names;
// max_angular_radps is written in rad/s as the field holds it (as the velocity commands are).
void VisitP3dxDriverOptions(OptionVisitor* visitor, P3dxDriverOptions* options);

// Empty when the options are usable; otherwise one line naming the first bad option by its key
// ("pulse_interval_s = 2.5: must be in (0, 2)"): each value within its range (the schema), then
// reconnect_max_s >= reconnect_initial_s and a subclass with conversion factors. The port is
// not judged here: the session opens it through its injected factory (the program checks it
// with CheckEndpoint before, p3dx_driver_config.h).
std::string CheckP3dxDriverOptions(const P3dxDriverOptions& options);

// The Markdown table of every key of the `p3dx:` section (docs/p3dx.md, "Options").
std::string P3dxDriverOptionsTable();

}  // namespace slammtt
