#include "drivers/command_auth/velocity_sender.h"

#include <cmath>
#include <stdexcept>

namespace slammtt {

void AddCommandRateOption(CommandLine* cl) {
  cl->AddOption("rate-hz", "HZ", "commands per second (default 10, 1 to 100)");
}

int64_t CommandPeriodUs(const CommandLine& cl) {
  const double rate_hz = cl.DoubleValue("rate-hz").value_or(kDefaultCommandRateHz);
  if (!(rate_hz >= 1.0 && rate_hz <= 100.0)) throw UsageError("--rate-hz must be in [1, 100]");
  return static_cast<int64_t>(std::llround(1e6 / rate_hz));
}

SignedVelocitySender::SignedVelocitySender(const CommandKey& key, const std::string& channel,
                                           Bus* bus, DriverClock* clock)
    : channel_(channel), signer_(key, channel, NewSenderId()), bus_(bus), clock_(clock) {}

void SignedVelocitySender::Send(double linear_mps, double angular_radps) {
  slammtt_msgs::velocity_command_t command{};
  command.utime = clock_->NowUtime();
  command.linear_mps = linear_mps;
  command.angular_radps = angular_radps;
  signer_.Sign(&command);
  const int64_t failed_before = bus_->failed_publishes();
  bus_->PublishMessage(channel_, command);
  if (bus_->failed_publishes() != failed_before) throw std::runtime_error("LCM publish failed");
}

}  // namespace slammtt
