// slammtt-drive: a minimal teleop for a base station or a test. Publishes signed
// VELOCITY_COMMAND (command_signature.h) at a fixed rate for a while, then a stop.
#include <cmath>
#include <memory>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/velocity_sender.h"
#include "drivers/common/driver_clock.h"
#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

namespace slammtt {
namespace {

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-drive", "--key FILE [--linear-mps V] [--angular-radps W] [options]",
                 "Drives the base: signed VELOCITY_COMMAND at --rate-hz for --duration-s, then "
                 "one stop command. The key is the robot's (p3dx.command_key_file).");
  AddStandardOptions(&cl);
  cl.AddOption("key", "FILE", "the command key shared with the robot (required)");
  cl.AddOption("linear-mps", "V", "forward speed (default 0)");
  cl.AddOption("angular-radps", "W", "turn rate, CCW positive (default 0)");
  cl.AddOption("duration-s", "S", "how long to send (default 1, at most 3600)");
  AddCommandRateOption(&cl);
  if (!cl.Parse(argc, argv)) return 0;
  const ProcessSettings settings = LoadProcessSettings(cl);
  const auto key_path = cl.Value("key");
  if (!key_path) throw UsageError("--key FILE is required");
  const double linear = cl.DoubleValue("linear-mps").value_or(0.0);
  const double angular = cl.DoubleValue("angular-radps").value_or(0.0);
  const double duration_s = cl.DoubleValue("duration-s").value_or(1.0);
  if (!(duration_s >= 0.0 && duration_s <= 3600.0)) {
    throw UsageError("--duration-s must be in [0, 3600]");
  }
  const int64_t period_us = CommandPeriodUs(cl);

  const CommandKey key = LoadCommandKeyFile(*key_path);
  LcmBus bus(settings.lcm_url);
  SystemDriverClock clock;
  SignedVelocitySender sender(key, settings.channels.Get("velocity_command"), &bus, &clock);
  // One command now and one every period while the duration lasts (due times start + k *
  // period < end), paced by the process's loop.
  SteadyMonotonicClock loop_clock;
  EventLoop loop(&bus, &loop_clock);
  const int64_t duration_us = static_cast<int64_t>(std::llround(duration_s * 1e6));
  const int64_t commands = (duration_us + period_us - 1) / period_us;
  const auto send_due = [&] {
    if (sender.sent() < commands) sender.Send(linear, angular);
  };
  send_due();
  loop.AddTimer(period_us, send_due);
  while (sender.sent() < commands && !ShutdownRequested()) loop.HandleTimeoutUs(period_us);
  sender.Send(0.0, 0.0);
  LogInfo() << "sent " << sender.sent() << " signed commands on " << sender.channel()
            << " (the last one a stop)";
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-drive", slammtt::Run);
}
