// Publishes signed VELOCITY_COMMAND (command_signature.h) for one sender: the time from the
// driver clock, a fresh counter and tag for every command. Shared by slammtt-drive and
// slammtt-teleop, so that both send exactly what the base driver checks.
#pragma once

#include <cstdint>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/command_signature.h"
#include "drivers/common/driver_clock.h"
#include "runtime/bus.h"
#include "runtime/command_line.h"

namespace slammtt {

// The base driver stops the robot when no command came for p3dx.command_timeout_s (0.5 s in
// config/robot.yaml): a sender repeats its command at this rate, five per timeout.
inline constexpr double kDefaultCommandRateHz = 10.0;

// --rate-hz of a sending program (slammtt-drive, slammtt-teleop): declared on `cl`, and read as
// the period between commands (default kDefaultCommandRateHz; UsageError outside 1-100 Hz).
void AddCommandRateOption(CommandLine* cl);
int64_t CommandPeriodUs(const CommandLine& cl);

class SignedVelocitySender {
 public:
  // `bus` and `clock` outlive the sender; the sender id is drawn from the system (NewSenderId).
  SignedVelocitySender(const CommandKey& key, const std::string& channel, Bus* bus,
                       DriverClock* clock);
  // One signed command stamped now. std::runtime_error when the bus cannot publish it.
  void Send(double linear_mps, double angular_radps);
  int64_t sent() const { return signer_.last_counter(); }
  const std::string& channel() const { return channel_; }

 private:
  std::string channel_;
  VelocityCommandSigner signer_;
  Bus* bus_;
  DriverClock* clock_;
};

}  // namespace slammtt
