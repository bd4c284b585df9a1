// slammtt-rplidar: the RPLIDAR A2 driver process. Options in docs/rplidar.md.
#include <iostream>
#include <memory>
#include <stdexcept>

#include "drivers/common/byte_stream.h"
#include "drivers/common/driver_clock.h"
#include "drivers/rplidar/rplidar_driver.h"
#include "drivers/rplidar/rplidar_driver_config.h"
#include "runtime/lcm_io.h"
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

    std::unique_ptr<lcm::LCM> lcm = OpenLcm(settings.lcm_url);
    LcmSink sink(lcm.get());
    SystemDriverClock clock;
    rplidar::RplidarDriver driver(
        options,
        [&options] {
          return OpenByteStream(options.port, options.baud, options.connect_timeout_ms);
        },
        &clock, &sink, settings.channels.Get("laser_scan"), settings.channels.Get("lidar_status"),
        settings.channels.Get("laser_geometry"));
    driver.Run([] { return ShutdownRequested(); });
    return 0;
  });
}
