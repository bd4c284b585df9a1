// The P3-DX driver as the program runs it: the device session (p3dx_session.h, pure) publishing
// its reports as ODOMETRY and BASE_STATUS on a MessageSink (p3dx_messages.h), its log lines in
// the process log, and the check of who sent a VELOCITY_COMMAND (drivers/command_auth: the
// signature binds the message's encoding and channel, so it is checked here, on the message).
// Everything the driver does with the robot is the session's; this is the bus around it.
#pragma once

#include <memory>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/command_signature.h"
#include "drivers/common/runtime_driver_log.h"
#include "drivers/p3dx/p3dx_session.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/base_status_t.hpp"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace slammtt {

struct P3dxDriverChannels {
  std::string odometry = "ODOMETRY";
  std::string base_status = "BASE_STATUS";
  std::string velocity_command = "VELOCITY_COMMAND";  // a signed command's tag covers it
};

// Publishes a session's reports on a bus.
class P3dxMessagePublisher : public P3dxSessionOutput {
 public:
  P3dxMessagePublisher(MessageSink* sink, const P3dxDriverChannels& channels);
  void OnBaseOdometry(const BaseOdometry& odometry) override;
  void OnBaseStatus(const BaseStatus& status) override;

 private:
  MessageSink* sink_;
  P3dxDriverChannels channels_;
};

class P3dxDriver {
 public:
  using State = P3dxSession::State;

  P3dxDriver(const P3dxDriverOptions& options, ByteStreamFactory factory, DriverClock* clock,
             MessageSink* sink, P3dxDriverChannels channels = P3dxDriverChannels{});

  // The key signed commands must carry (with command_authentication kSigned; without a key every
  // command is refused).
  void SetCommandKey(const CommandKey& key);
  // A VELOCITY_COMMAND from the bus: with command_authentication kSigned, accepted only when
  // signed with the key, fresh and not replayed (VelocityCommandVerifier); then handed to the
  // session (P3dxSession::AcceptCommand), else counted there as refused. Nothing after
  // Shutdown().
  void ReceiveVelocityCommand(const slammtt_msgs::velocity_command_t& command);
  // A command from someone allowed to drive the robot, unchecked (P3dxSession::HandleCommand).
  void HandleVelocityCommand(const slammtt_msgs::velocity_command_t& command);

  // The session's (p3dx_session.h).
  void Poll(int max_wait_ms) { session_.Poll(max_wait_ms); }
  void Shutdown() { session_.Shutdown(); }
  int MillisecondsUntilDue() const { return session_.MillisecondsUntilDue(); }
  int LinkPollDescriptor() const { return session_.LinkPollDescriptor(); }
  bool link_open() const { return session_.link_open(); }
  State state() const { return session_.state(); }
  static const char* StateName(State state) { return P3dxSession::StateName(state); }
  int64_t commands_skipped() const { return session_.commands_skipped(); }
  int64_t commands_refused() const { return session_.commands_refused(); }
  const P3dxDecoderCounters& decoder_counters() const { return session_.decoder_counters(); }

  // The BASE_STATUS as it would be published now.
  slammtt_msgs::base_status_t Status() const;

 private:
  P3dxDriverOptions options_;
  DriverClock* clock_;
  std::string velocity_command_channel_;
  std::unique_ptr<VelocityCommandVerifier> verifier_;
  // Before the session, which uses them until its destructor's Shutdown() has run.
  P3dxMessagePublisher publisher_;
  RuntimeDriverLog log_;
  P3dxSession session_;
};

}  // namespace slammtt
