// slammtt-rplidar: the RPLIDAR A2 driver process. Options in docs/rplidar.md.
#include <iostream>
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
    rplidar::AddRplidarDriverOptions(&command_line);
    if (!command_line.Parse(arg_count, args)) return 0;
    if (command_line.Flag("options-table")) {
      std::cout << rplidar::RplidarDriverOptionsTable();
      return 0;
    }
    ProcessSettings settings = LoadProcessSettings(command_line);
    const Config section = settings.config.Child("rplidar");
    rplidar::RplidarDriverOptions options = rplidar::ReadRplidarDriverOptions(section);
    rplidar::ApplyRplidarDriverCommandLine(command_line, &options);
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
