// slammtt-p3dx: the Pioneer P3-DX base driver (see p3dx_driver.h and docs/p3dx.md).
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/command_auth/command_key.h"
#include "drivers/p3dx/p3dx_driver.h"
#include "drivers/p3dx/p3dx_driver_config.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"
#include "slammtt_msgs/velocity_command_t.hpp"

namespace {

// The loop wakes at the latest this often even when no timer is due (a safety net: every timer
// of the driver is announced by MillisecondsUntilDue()).
constexpr int kMaxWaitMs = 1000;
// A link without a poll descriptor (none of ours) is read with this bounded wait instead.
constexpr int kLinkWithoutDescriptorWaitMs = 10;

int Main(int argc, char** argv) {
  using namespace slammtt;
  CommandLine cl("slammtt-p3dx", "[options]",
                 "Pioneer P3-DX base driver: publishes ODOMETRY and BASE_STATUS, drives the base "
                 "from VELOCITY_COMMAND, stops it when commands stop and on exit.");
  AddStandardOptions(&cl);
  AddP3dxDriverOptions(&cl);
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("options-table")) {
    std::cout << P3dxDriverOptionsTable();
    return 0;
  }
  const ProcessSettings settings = LoadProcessSettings(cl);
  const Config section = settings.config.Child("p3dx");
  P3dxDriverOptions options = ReadP3dxDriverOptions(section);
  section.CheckUnused();
  ApplyP3dxDriverCommandLine(cl, &options);
  try {
    CheckCommandAuthenticationForBus(options, settings.lcm_url);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  std::optional<CommandKey> key;
  if (!options.command_key_file.empty()) key = LoadCommandKeyFile(options.command_key_file);

  LcmBus bus(settings.lcm_url);
  SteadyMonotonicClock loop_clock;
  EventLoop loop(&bus, &loop_clock);
  SystemDriverClock clock;
  P3dxDriverChannels channels;
  channels.odometry = settings.channels.Get("odometry");
  channels.base_status = settings.channels.Get("base_status");
  channels.velocity_command = settings.channels.Get("velocity_command");
  P3dxDriver driver(
      options, [](const std::string& endpoint, int baud) { return OpenByteStream(endpoint, baud); },
      &clock, &bus, channels);
  if (key) driver.SetCommandKey(*key);

  // A command is sent the moment it arrives. An exception of the driver is rethrown by the loop
  // once LCM's dispatch has returned (bus.h), and ends the process (the driver's destructor
  // stops the robot); an undecodable message is counted and skipped by the bus.
  bus.Subscribe<slammtt_msgs::velocity_command_t>(
      channels.velocity_command,
      [&driver](const slammtt_msgs::velocity_command_t& command) {
        driver.ReceiveVelocityCommand(command);
      });
  // A SIP is handled the moment its bytes arrive (the link's descriptor changes as it reopens).
  loop.AddFdHook([&driver] { return driver.LinkPollDescriptor(); }, [&driver] { driver.Poll(0); });
  LogInfo() << "driving " << options.port << " (max " << options.max_linear_mps << " m/s, "
            << options.max_angular_radps << " rad/s, command timeout "
            << options.command_timeout_s << " s)";
  if (options.command_authentication == P3dxDriverOptions::CommandAuthentication::kNone) {
    LogWarning() << "VELOCITY_COMMAND is not authenticated (p3dx.command_authentication: none): "
                    "any program on this computer can drive the robot, and so can any host that "
                    "reaches the bus's UDP port on this computer unless a firewall stops it "
                    "(docs/robot.md)";
  } else if (key) {
    LogInfo() << "VELOCITY_COMMAND must be signed with the key of " << options.command_key_file
              << " (freshness window " << options.command_max_age_s << " s)";
  } else {
    LogWarning() << "no command key (p3dx.command_key_file): every VELOCITY_COMMAND is refused "
                    "and the robot does not move (docs/robot.md, \"Who can drive the robot\")";
  }

  // One wait for everything (the bus, the link, the shutdown request, the driver's next timer);
  // then Poll(0) does what is due and reads only what is there.
  while (!ShutdownRequested()) {
    driver.Poll(0);
    int wait_ms = std::min(driver.MillisecondsUntilDue(), kMaxWaitMs);
    if (driver.LinkPollDescriptor() < 0 && driver.link_open()) {
      wait_ms = std::min(wait_ms, kLinkWithoutDescriptorWaitMs);
    }
    loop.HandleTimeout(std::max(wait_ms, 0));
  }
  driver.Shutdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return slammtt::ProcessMain(argc, argv, "slammtt-p3dx", Main); }
