// slammtt-p3dx: the Pioneer P3-DX base driver (see p3dx_driver.h and docs/p3dx.md).
#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
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
#include "runtime/lcm_io.h"
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

  std::unique_ptr<lcm::LCM> lcm = OpenLcm(settings.lcm_url);
  LcmSink sink(lcm.get());
  SystemDriverClock clock;
  P3dxDriverChannels channels;
  channels.odometry = settings.channels.Get("odometry");
  channels.base_status = settings.channels.Get("base_status");
  channels.velocity_command = settings.channels.Get("velocity_command");
  P3dxDriver driver(
      options, [](const std::string& endpoint, int baud) { return OpenByteStream(endpoint, baud); },
      &clock, &sink, channels);
  if (key) driver.SetCommandKey(*key);

  // An exception must not unwind through LCM's C dispatch: the handler keeps the first one and
  // the loop rethrows it once handle() has returned (the driver's destructor stops the robot).
  struct Context {
    P3dxDriver* driver;
    int64_t undecodable = 0;
    std::string error;
  } context{&driver, 0, {}};
  lcm->subscribeFunction(
      settings.channels.Get("velocity_command"),
      +[](const lcm::ReceiveBuffer* buffer, const std::string& channel, Context* c) {
        slammtt_msgs::velocity_command_t command;
        if (!Decode(buffer->data, static_cast<int>(buffer->data_size), &command)) {
          if (IsReportable(++c->undecodable)) {
            LogWarning() << channel << ": undecodable message skipped (" << c->undecodable
                         << " so far)";
          }
          return;
        }
        try {
          c->driver->ReceiveVelocityCommand(command);
        } catch (const std::exception& e) {
          if (c->error.empty()) c->error = e.what();
        }
      },
      &context);
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

  // One wait for everything: the bus (VELOCITY_COMMAND is sent the moment it arrives), the link
  // (a SIP is handled the moment its bytes arrive), the shutdown request, and the driver's next
  // timer. Then Poll(0) does what is due and reads only what is there.
  while (!ShutdownRequested()) {
    driver.Poll(0);
    pollfd fds[3] = {{lcm->getFileno(), POLLIN, 0}, {ShutdownFd(), POLLIN, 0}, {-1, POLLIN, 0}};
    nfds_t count = 2;
    int wait_ms = std::min(driver.MillisecondsUntilDue(), kMaxWaitMs);
    if (const int link_fd = driver.LinkPollDescriptor(); link_fd >= 0) {
      fds[2].fd = link_fd;
      count = 3;
    } else if (driver.link_open()) {
      wait_ms = std::min(wait_ms, kLinkWithoutDescriptorWaitMs);
    }
    const int ready = poll(fds, count, wait_ms);
    if (ready < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("poll failed: ") + std::strerror(errno));
    }
    if (ready > 0 && (fds[0].revents & POLLIN) != 0) {
      // Everything that is waiting, without blocking.
      do {
        if (lcm->handle() != 0) throw std::runtime_error("LCM failed while receiving");
        if (!context.error.empty()) throw std::runtime_error(context.error);
      } while (poll(fds, 1, 0) > 0 && (fds[0].revents & POLLIN) != 0);
    }
  }
  driver.Shutdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return slammtt::ProcessMain(argc, argv, "slammtt-p3dx", Main); }
