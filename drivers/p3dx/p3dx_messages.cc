#include "drivers/p3dx/p3dx_messages.h"

namespace slammtt {

const char* CommandAuthName(CommandAuthState state) {
  switch (state) {
    case CommandAuthState::kNone: return "none (local only)";
    case CommandAuthState::kSigned: return "hmac-sha256";
    case CommandAuthState::kSignedWithoutKey:
      return "hmac-sha256 without a key: every command refused";
  }
  return "unknown";
}

BaseCommand BaseCommandFromMessage(const slammtt_msgs::velocity_command_t& message) {
  BaseCommand command;
  command.linear_mps = message.linear_mps;
  command.angular_radps = message.angular_radps;
  return command;
}

slammtt_msgs::odometry_t OdometryMessage(const BaseOdometry& odometry) {
  slammtt_msgs::odometry_t message{};
  message.utime = odometry.utime;
  message.sequence = odometry.sequence;
  message.x_m = odometry.reading.x_m;
  message.y_m = odometry.reading.y_m;
  message.heading_rad = odometry.reading.heading_rad;
  message.linear_velocity_mps = odometry.reading.linear_velocity_mps;
  message.angular_velocity_radps = odometry.reading.angular_velocity_radps;
  message.left_wheel_velocity_mps = odometry.reading.left_wheel_velocity_mps;
  message.right_wheel_velocity_mps = odometry.reading.right_wheel_velocity_mps;
  return message;
}

slammtt_msgs::base_status_t BaseStatusMessage(const BaseStatus& status) {
  slammtt_msgs::base_status_t message{};
  message.utime = status.utime;
  message.connected = status.connected;
  message.state = BaseStateName(status.state);
  message.endpoint = status.endpoint;
  message.robot_name = status.robot_name;
  message.robot_class = status.robot_class;
  message.robot_subclass = status.robot_subclass;
  message.battery_v = status.battery_v;
  message.left_wheel_stall = status.left_wheel_stall;
  message.right_wheel_stall = status.right_wheel_stall;
  message.bumpers = status.bumpers;
  message.motors_enabled = status.motors_enabled;
  message.command_timeout_stop = status.command_timeout_stop;
  message.sips_received = status.sips_received;
  message.checksum_errors = status.checksum_errors;
  message.short_packets = status.short_packets;
  message.reconnects = status.reconnects;
  message.last_error = status.last_error;
  message.command_auth = CommandAuthName(status.command_auth);
  message.commands_accepted = status.commands_accepted;
  message.commands_unauthenticated = status.commands_unauthenticated;
  message.commands_stale = status.commands_stale;
  message.commands_replayed = status.commands_replayed;
  return message;
}

}  // namespace slammtt
