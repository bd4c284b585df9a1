// slammtt-p3dx-emulator: a Pioneer P3-DX microcontroller on a pseudo-terminal or a TCP port.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "common/number_text.h"

#include "drivers/p3dx/p3dx_emulator.h"
#include "runtime/command_line.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

namespace {

int Main(int argc, char** argv) {
  using namespace slammtt;
  CommandLine cl("slammtt-p3dx-emulator", "[options]",
                 "Emulates a Pioneer P3-DX base (ARCOS protocol: SYNC handshake, SIPs every "
                 "100 ms, VEL/RVEL/VEL2/ENABLE/STOP/ESTOP/CLOSE, 2 s watchdog) on a "
                 "pseudo-terminal or a TCP port, with scheduled faults. Prints the endpoint a "
                 "driver should open as its first line on stdout.");
  cl.AddOption("link", "PATH", "publish the pty as this symlink (e.g. /tmp/p3dx), kept pointing "
                               "at the current pty across simulated unplugs");
  cl.AddOption("tcp", "PORT", "serve on a TCP port instead of a pty (0 = any free port)");
  cl.AddOption("bind", "HOST", "address to listen on with --tcp (default 127.0.0.1)");
  cl.AddOption("subclass", "NAME", "subclass in the SYNC2 reply: p3dx (default) or p3dx-sh");
  cl.AddOption("name", "NAME", "robot name in the SYNC2 reply (default slammtt-emulator)");
  cl.AddOption("battery-v", "VOLTS", "battery voltage reported (default 12.5)");
  cl.AddOption("sip-cycle-ms", "MS", "SIP period (default 100)");
  cl.AddOption("watchdog-ms", "MS", "firmware watchdog (default 2000)");
  cl.AddOption("sonars", "N", "sonar readings per SIP (default 0)");
  cl.AddFlag("signed-thpos", "send THPOS in [-2048, 2047] instead of [0, 4095]");
  cl.AddFlag("short-sip", "send only the classic SIP fields (no BATTERYX10, ROTVEL, ...)");
  cl.AddOption("seed", "N", "seed of the garbage bytes (default 1)");
  cl.AddOption("start-moving", "V,W",
               "start in a session left open by an earlier client, moving at V m/s, W rad/s");
  cl.AddRepeatedOption("fault", "KIND@SECONDS[:ARG]",
                       "scheduled fault: garbage[:BYTES], bad-checksum[:N], drop[:BYTES], "
                       "short[:N], truncate[:N], silence[:S], mute[:S], disconnect[:S], "
                       "bumper[:LEFT,RIGHT], stall[:LEFT,RIGHT]");
  cl.AddFlag("quiet", "print only warnings and errors", 'q');
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("quiet")) SetLogLevel(LogLevel::kWarning);

  P3dxEmulatorOptions options;
  if (auto port = cl.IntValue("tcp")) {
    if (*port < 0 || *port > 65535) throw UsageError("--tcp: port out of range");
    options.use_pty = false;
    options.tcp_port = static_cast<int>(*port);
    options.tcp_bind_host = cl.ValueOr("bind", "127.0.0.1");
    if (cl.Value("link")) throw UsageError("--link applies to a pty, not to --tcp");
  } else {
    if (cl.Value("bind")) throw UsageError("--bind applies to --tcp");
    options.pty_link = cl.ValueOr("link", "");
  }
  P3dxRobotModelOptions& robot = options.robot;
  robot.identity.subclass = cl.ValueOr("subclass", robot.identity.subclass);
  if (!P3dxConversionForSubclass(robot.identity.subclass)) {
    throw UsageError("--subclass: no conversion factors for '" + robot.identity.subclass + "'");
  }
  robot.identity.name = cl.ValueOr("name", robot.identity.name);
  if (auto v = cl.DoubleValue("battery-v")) robot.battery_v = *v;
  // Ranges are checked on the 64-bit value, before it is narrowed to int.
  auto bounded = [&cl](const char* name, int64_t minimum, int64_t maximum, int* value) {
    if (auto v = cl.IntValue(name)) {
      if (*v < minimum || *v > maximum) {
        throw UsageError(std::string("--") + name + ": " + std::to_string(minimum) + ".." +
                         std::to_string(maximum));
      }
      *value = static_cast<int>(*v);
    }
  };
  bounded("sip-cycle-ms", 10, 1000, &robot.sip_cycle_ms);
  bounded("watchdog-ms", 100, 3600000, &robot.watchdog_ms);
  bounded("sonars", 0, 32, &robot.sonar_count);
  if (auto v = cl.IntValue("seed")) robot.seed = static_cast<uint32_t>(*v);
  robot.signed_thpos = cl.Flag("signed-thpos");
  robot.extended_sip = !cl.Flag("short-sip");
  if (robot.battery_v < 0.0 || robot.battery_v > 25.5) throw UsageError("--battery-v: 0..25.5");
  for (const std::string& text : cl.Values("fault")) {
    try {
      options.faults.push_back(ParseP3dxEmulatorFault(text));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--fault: ") + e.what());
    }
  }

  P3dxEmulator emulator(options);
  if (auto start = cl.Value("start-moving")) {
    // Whole numbers of the text only, finite and within what the robot can do (a NaN here
    // would become the robot's pose).
    const size_t comma = start->find(',');
    auto number = [&start](const std::string& text, double limit) {
      const std::optional<double> value = ParseFiniteDouble(text);
      if (!value || std::abs(*value) > limit) {
        throw UsageError("--start-moving expects V,W (|V| <= 2 m/s, |W| <= 6 rad/s), got '" +
                         *start + "'");
      }
      return *value;
    };
    if (comma == std::string::npos) number("", 0.0);
    const double v = number(start->substr(0, comma), 2.0);
    const double w = number(start->substr(comma + 1), 6.0);
    emulator.WithModel([&](P3dxRobotModel& model) {
      model.StartConnected(v, w, P3dxEmulator::NowUs());
      return 0;
    });
  }
  std::cout << emulator.Endpoint() << std::endl;
  LogInfo() << "emulating '" << robot.identity.name << "' (" << robot.identity.subclass
            << ") on " << emulator.Endpoint();
  emulator.Run([] { return ShutdownRequested(); });
  emulator.WithModel([&](P3dxRobotModel& model) {
    LogInfo() << "SIPs sent " << model.sips_sent() << ", commands received "
              << model.received().size() << ", bad packets received "
              << model.bad_packets_received() << ", watchdog stops " << model.watchdog_stops()
              << ", bytes the host did not take " << emulator.bytes_dropped();
    return 0;
  });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-p3dx-emulator", Main);
}
