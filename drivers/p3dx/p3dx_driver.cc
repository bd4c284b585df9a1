#include "drivers/p3dx/p3dx_driver.h"

#include <utility>

#include "drivers/p3dx/p3dx_messages.h"

namespace slammtt {

P3dxMessagePublisher::P3dxMessagePublisher(MessageSink* sink, const P3dxDriverChannels& channels)
    : sink_(sink), channels_(channels) {}

void P3dxMessagePublisher::OnBaseOdometry(const BaseOdometry& odometry) {
  sink_->PublishMessage(channels_.odometry, OdometryMessage(odometry));
}

void P3dxMessagePublisher::OnBaseStatus(const BaseStatus& status) {
  sink_->PublishMessage(channels_.base_status, BaseStatusMessage(status));
}

P3dxDriver::P3dxDriver(const P3dxDriverOptions& options, ByteStreamFactory factory,
                       DriverClock* clock, MessageSink* sink, P3dxDriverChannels channels)
    : options_(options),
      clock_(clock),
      velocity_command_channel_(channels.velocity_command),
      publisher_(sink, channels),
      session_(options, std::move(factory), clock, &publisher_, &log_) {}

void P3dxDriver::SetCommandKey(const CommandKey& key) {
  CommandVerifierOptions verifier_options;
  verifier_options.max_age_s = options_.command_max_age_s;
  verifier_ = std::make_unique<VelocityCommandVerifier>(key, velocity_command_channel_,
                                                        verifier_options);
  session_.SetCommandKeyLoaded();
}

void P3dxDriver::ReceiveVelocityCommand(const slammtt_msgs::velocity_command_t& command) {
  // A stopped session takes nothing, so the verifier does not remember a counter for it.
  if (session_.state() == State::kStopped) return;
  if (options_.command_authentication == P3dxDriverOptions::CommandAuthentication::kSigned) {
    const CommandVerdict verdict = verifier_ ? verifier_->Check(command, clock_->NowUtime())
                                             : CommandVerdict::kUnauthenticated;
    if (verdict != CommandVerdict::kAccepted) {
      const CommandRefusal reason = verdict == CommandVerdict::kStale ? CommandRefusal::kStale
                                    : verdict == CommandVerdict::kReplayed
                                        ? CommandRefusal::kReplayed
                                        : CommandRefusal::kUnauthenticated;
      session_.RefuseCommand(
          reason, verifier_ ? CommandVerdictName(verdict)
                            : "no command key (set p3dx.command_key_file, docs/robot.md)");
      return;
    }
  }
  session_.AcceptCommand(BaseCommandFromMessage(command));
}

void P3dxDriver::HandleVelocityCommand(const slammtt_msgs::velocity_command_t& command) {
  session_.HandleCommand(BaseCommandFromMessage(command));
}

slammtt_msgs::base_status_t P3dxDriver::Status() const {
  return BaseStatusMessage(session_.Status());
}

}  // namespace slammtt
