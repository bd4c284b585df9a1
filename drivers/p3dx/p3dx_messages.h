// The P3-DX session's plain structs as LCM messages: VELOCITY_COMMAND -> BaseCommand,
// BaseOdometry -> odometry_t (ODOMETRY), BaseStatus -> base_status_t (BASE_STATUS). Field for
// field; the only conversions are the state and command_auth names.
#pragma once

#include "drivers/p3dx/p3dx_session_output.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {

// The set-point of a command; its utime, sender_id, counter and tag are the signature's
// (command_signature.h), checked before the command is handed on.
BaseCommand BaseCommandFromMessage(const slammtt_msgs::velocity_command_t& message);
slammtt_msgs::odometry_t OdometryMessage(const BaseOdometry& odometry);
slammtt_msgs::base_status_t BaseStatusMessage(const BaseStatus& status);

// base_status_t.command_auth: "none (local only)", "hmac-sha256",
// "hmac-sha256 without a key: every command refused".
const char* CommandAuthName(CommandAuthState state);

}  // namespace slammtt
