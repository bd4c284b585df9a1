// The P3-DX session's plain structs to and from VELOCITY_COMMAND, ODOMETRY and BASE_STATUS,
// field for field.
#include "drivers/p3dx/p3dx_messages.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace slammtt {
namespace {

TEST(P3dxMessagesTest, VelocityCommandGivesItsSetPoint) {
  slammtt_msgs::velocity_command_t message{};
  message.utime = 1700000000000001;
  message.linear_mps = 0.35;
  message.angular_radps = -0.75;
  message.sender_id = 77;
  message.counter = 5;
  message.tag[0] = 1;
  const BaseCommand command = BaseCommandFromMessage(message);
  EXPECT_EQ(command.linear_mps, 0.35);
  EXPECT_EQ(command.angular_radps, -0.75);
}

TEST(P3dxMessagesTest, OdometryMapsEveryField) {
  BaseOdometry odometry;
  odometry.utime = 1700000000123456;
  odometry.sequence = 9;
  odometry.reading.x_m = 1.5;
  odometry.reading.y_m = -2.25;
  odometry.reading.heading_rad = 3.0;
  odometry.reading.linear_velocity_mps = 0.4;
  odometry.reading.angular_velocity_radps = -0.2;
  odometry.reading.left_wheel_velocity_mps = 0.38;
  odometry.reading.right_wheel_velocity_mps = 0.42;
  const slammtt_msgs::odometry_t message = OdometryMessage(odometry);
  EXPECT_EQ(message.utime, 1700000000123456);
  EXPECT_EQ(message.sequence, 9);
  EXPECT_EQ(message.x_m, 1.5);
  EXPECT_EQ(message.y_m, -2.25);
  EXPECT_EQ(message.heading_rad, 3.0);
  EXPECT_EQ(message.linear_velocity_mps, 0.4);
  EXPECT_EQ(message.angular_velocity_radps, -0.2);
  EXPECT_EQ(message.left_wheel_velocity_mps, 0.38);
  EXPECT_EQ(message.right_wheel_velocity_mps, 0.42);
}

TEST(P3dxMessagesTest, BaseStatusMapsEveryField) {
  BaseStatus status;
  status.utime = 1700000000654321;
  status.connected = true;
  status.state = BaseState::kRunning;
  status.endpoint = "tcp://127.0.0.1:8101";
  status.robot_name = "slammtt-emulator";
  status.robot_class = "Pioneer";
  status.robot_subclass = "p3dx-sh";
  status.battery_v = 12.5;
  status.left_wheel_stall = true;
  status.right_wheel_stall = false;
  status.bumpers = 0x0103;
  status.motors_enabled = true;
  status.command_timeout_stop = true;
  status.sips_received = 21;
  status.checksum_errors = 22;
  status.short_packets = 23;
  status.reconnects = 24;
  status.last_error = "no valid SIP for 1 s";
  status.command_auth = CommandAuthState::kSigned;
  status.commands_accepted = 25;
  status.commands_unauthenticated = 26;
  status.commands_stale = 27;
  status.commands_replayed = 28;
  const slammtt_msgs::base_status_t message = BaseStatusMessage(status);
  EXPECT_EQ(message.utime, 1700000000654321);
  EXPECT_TRUE(message.connected);
  EXPECT_EQ(message.state, "running");
  EXPECT_EQ(message.endpoint, "tcp://127.0.0.1:8101");
  EXPECT_EQ(message.robot_name, "slammtt-emulator");
  EXPECT_EQ(message.robot_class, "Pioneer");
  EXPECT_EQ(message.robot_subclass, "p3dx-sh");
  EXPECT_EQ(message.battery_v, 12.5);
  EXPECT_TRUE(message.left_wheel_stall);
  EXPECT_FALSE(message.right_wheel_stall);
  EXPECT_EQ(message.bumpers, 0x0103);
  EXPECT_TRUE(message.motors_enabled);
  EXPECT_TRUE(message.command_timeout_stop);
  EXPECT_EQ(message.sips_received, 21);
  EXPECT_EQ(message.checksum_errors, 22);
  EXPECT_EQ(message.short_packets, 23);
  EXPECT_EQ(message.reconnects, 24);
  EXPECT_EQ(message.last_error, "no valid SIP for 1 s");
  EXPECT_EQ(message.command_auth, "hmac-sha256");
  EXPECT_EQ(message.commands_accepted, 25);
  EXPECT_EQ(message.commands_unauthenticated, 26);
  EXPECT_EQ(message.commands_stale, 27);
  EXPECT_EQ(message.commands_replayed, 28);
}

TEST(P3dxMessagesTest, StateAndCommandAuthNamesAreTheMessagesSpelling) {
  const std::vector<std::pair<BaseState, std::string>> states = {
      {BaseState::kConnecting, "connecting"},
      {BaseState::kReconnecting, "reconnecting"},
      {BaseState::kSyncing, "syncing"},
      {BaseState::kStoppingEarlierSession, "stopping-earlier-session"},
      {BaseState::kClosingEarlierSession, "closing-earlier-session"},
      {BaseState::kOpening, "opening"},
      {BaseState::kRunning, "running"},
      {BaseState::kStopped, "stopped"}};
  for (const auto& [state, name] : states) {
    BaseStatus status;
    status.state = state;
    EXPECT_EQ(BaseStatusMessage(status).state, name);
  }
  const std::vector<std::pair<CommandAuthState, std::string>> auth = {
      {CommandAuthState::kNone, "none (local only)"},
      {CommandAuthState::kSigned, "hmac-sha256"},
      {CommandAuthState::kSignedWithoutKey, "hmac-sha256 without a key: every command refused"}};
  for (const auto& [state, name] : auth) {
    BaseStatus status;
    status.command_auth = state;
    EXPECT_EQ(BaseStatusMessage(status).command_auth, name);
  }
}

}  // namespace
}  // namespace slammtt
