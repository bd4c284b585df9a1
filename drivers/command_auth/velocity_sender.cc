#include "drivers/command_auth/velocity_sender.h"

#include <stdexcept>

namespace slammtt {

SignedVelocitySender::SignedVelocitySender(const CommandKey& key, const std::string& channel,
                                           lcm::LCM* lcm, DriverClock* clock)
    : channel_(channel), signer_(key, channel, NewSenderId()), lcm_(lcm), clock_(clock) {}

void SignedVelocitySender::Send(double linear_mps, double angular_radps) {
  slammtt_msgs::velocity_command_t command{};
  command.utime = clock_->NowUtime();
  command.linear_mps = linear_mps;
  command.angular_radps = angular_radps;
  signer_.Sign(&command);
  if (lcm_->publish(channel_, &command) != 0) throw std::runtime_error("LCM publish failed");
}

}  // namespace slammtt
