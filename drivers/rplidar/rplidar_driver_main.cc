// slammtt-rplidar: the RPLIDAR A2 driver process. Options in docs/rplidar.md.
#include <memory>
#include <stdexcept>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/common/loop_waits.h"
#include "drivers/rplidar/rplidar_driver.h"
#include "drivers/rplidar/rplidar_driver_config.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-rplidar", [](int arg_count, char** args) {
    using namespace slammtt;
    CommandLine command_line("slammtt-rplidar", "[options]",
                             "RPLIDAR A2 driver: publishes LASER_SCAN per revolution and "
                             "LIDAR_STATUS; serial port through libserialport or a TCP bridge.");
    AddStandardOptions(&command_line);
    command_line.AddOption("port", "PORT",
                           "serial port (/dev/ttyUSB0) or tcp://HOST:PORT (default: rplidar.port)");
    command_line.AddOption("baud", "RATE", "serial baud rate (default: rplidar.baud, 115200)");
    command_line.AddOption("mode", "MODE", "scan mode: standard or express (default: express)");
    if (!command_line.Parse(arg_count, args)) return 0;
    ProcessSettings settings = LoadProcessSettings(command_line);
    const Config section = settings.config.Child("rplidar");
    rplidar::RplidarDriverOptions options = rplidar::ReadRplidarDriverOptions(section);
    section.CheckUnused();
    if (auto port = command_line.Value("port")) options.port = *port;
    if (auto baud = command_line.IntValue("baud")) {
      if (*baud <= 0 || *baud > 10000000) throw UsageError("--baud must be a positive rate");
      options.baud = static_cast<int>(*baud);
    }
    if (auto mode = command_line.Value("mode")) {
      try {
        options.scan_mode = rplidar::ParseScanMode(*mode);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--mode: ") + e.what());
      }
    }
    try {
      rplidar::CheckRplidarDriverOptions(options);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("rplidar.port / --port: ") + e.what());
    }

    LcmBus bus(settings.lcm_url);
    SteadyMonotonicClock loop_clock;
    EventLoop loop(&bus, &loop_clock);
    // The session is written as blocking calls with bounded waits: each of its waits (for the
    // link, or a sleep) is a turn of the loop (drivers/common/loop_waits.h), so the process's
    // one wait is the loop's.
    SystemDriverClock system_clock;
    LoopWaitingDriverClock clock(&system_clock, &loop);
    rplidar::RplidarDriver driver(
        options,
        [&options, &loop] {
          return std::make_unique<LoopWaitingByteStream>(
              OpenByteStream(options.port, options.baud, options.connect_timeout_ms), &loop);
        },
        &clock, &bus, settings.channels.Get("laser_scan"), settings.channels.Get("lidar_status"),
        settings.channels.Get("laser_geometry"));
    driver.Run([] { return ShutdownRequested(); });
    return 0;
  });
}
