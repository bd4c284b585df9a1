// slammtt-rplidar-emulator: an RPLIDAR A2 on a pseudo-terminal or a TCP port, scanning a
// simple room, with scheduled fault injection. Options in docs/rplidar.md.

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/common/fault_schedule.h"
#include "drivers/rplidar/rplidar_emulator_faults.h"
#include "drivers/rplidar/rplidar_emulator_server.h"
#include "runtime/log.h"
#include "runtime/output_file.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

namespace {

using namespace slammtt;
using namespace slammtt::rplidar;

RplidarEmulatorFault ParseFault(const std::string& text) {
  try {
    return ParseRplidarEmulatorFault(text);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--fault: ") + e.what());
  }
}

void Inject(const RplidarEmulatorFault& fault, RplidarEmulatorServer* server) {
  using Kind = RplidarEmulatorFault::Kind;
  const double argument = fault.argument;
  LogInfo() << "fault: " << fault.name << " (" << argument << ")";
  switch (fault.kind) {
    case Kind::kGarbage: server->InjectGarbage(static_cast<size_t>(argument)); break;
    case Kind::kBadChecksum: server->CorruptPackets(static_cast<int>(argument)); break;
    case Kind::kDrop: server->DropBytes(static_cast<int>(argument)); break;
    case Kind::kSilence: server->Silence(static_cast<int>(argument * 1000)); break;
    case Kind::kMute: server->Mute(static_cast<int>(argument * 1000)); break;
    case Kind::kDisconnect: server->Disconnect(static_cast<int>(argument * 1000)); break;
  }
}

DeviceHealth ParseHealth(const std::string& text) {
  DeviceHealth health;
  if (text == "good") return health;
  const size_t colon = text.find(':');
  const std::string status = text.substr(0, colon);
  if (status == "warning") {
    health.status = HealthStatus::kWarning;
  } else if (status == "error") {
    health.status = HealthStatus::kError;
  } else {
    throw UsageError("--health " + text + ": expected good, warning:CODE or error:CODE");
  }
  if (colon != std::string::npos) {
    try {
      size_t used = 0;
      const unsigned long code = std::stoul(text.substr(colon + 1), &used, 0);
      if (used != text.size() - colon - 1 || code > 0xFFFF) throw std::out_of_range("code");
      health.error_code = static_cast<uint16_t>(code);
    } catch (const std::exception&) {
      throw UsageError("--health " + text + ": CODE is a number 0..65535 (0x.. allowed)");
    }
  }
  return health;
}

// An OutputFile: whole when it appears, never written through a link planted beside it.
void WriteEndpointFile(const std::string& path, const std::string& endpoint) {
  OutputFile file(path);
  const std::string line = endpoint + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file.stream()) != line.size()) {
    throw std::runtime_error(path + ": cannot write the endpoint file");
  }
  file.Commit();
}

}  // namespace

int main(int argc, char** argv) {
  return ProcessMain(argc, argv, "slammtt-rplidar-emulator", [](int arg_count, char** args) {
    CommandLine command_line(
        "slammtt-rplidar-emulator", "[options]",
        "Emulates an RPLIDAR A2 on a pseudo-terminal (default) or a TCP port: answers STOP, "
        "RESET, SCAN, FORCE_SCAN, EXPRESS_SCAN (mode 0), GET_INFO, GET_HEALTH, GET_SAMPLERATE, "
        "GET_ACC_BOARD_FLAG and SET_MOTOR_PWM, scanning a room with pillars and a box.");
    command_line.AddOption("tcp", "PORT", "serve on this TCP port instead of a pty (0: any)");
    command_line.AddOption("bind", "HOST", "TCP address to listen on (default 127.0.0.1)");
    command_line.AddOption("link", "PATH", "keep a symlink to the pty here (stable across re-creation)");
    command_line.AddOption("endpoint-file", "FILE",
                           "write the endpoint a driver should open to FILE once ready");
    command_line.AddOption("seed", "N", "noise seed (default 1)");
    command_line.AddOption("rotation-hz", "HZ", "scan rate (default 10)");
    command_line.AddOption("noise-m", "M", "range noise standard deviation (default 0.005)");
    command_line.AddFlag("accessory-board", "answer GET_ACC_BOARD_FLAG with PWM motor control");
    command_line.AddOption("health", "STATE", "good, warning:CODE or error:CODE (default good)");
    command_line.AddFlag("health-persists", "a RESET does not clear the health problem");
    command_line.AddRepeatedOption(
        "fault", "KIND@S[:ARG]",
        "at S seconds: garbage[:BYTES=100], bad-checksum[:PACKETS=1], drop[:PACKETS=1], "
        "silence[:SECONDS=3], mute[:SECONDS=3], disconnect[:SECONDS=3]");
    command_line.AddFlag("verbose", "print debug messages", 'v');
    command_line.AddFlag("quiet", "print only warnings and errors", 'q');
    if (!command_line.Parse(arg_count, args)) return 0;
    if (command_line.Flag("verbose")) SetLogLevel(LogLevel::kDebug);
    if (command_line.Flag("quiet")) SetLogLevel(LogLevel::kWarning);

    RplidarDeviceOptions device;
    if (auto seed = command_line.IntValue("seed")) device.seed = static_cast<uint64_t>(*seed);
    if (auto hz = command_line.DoubleValue("rotation-hz")) {
      if (*hz < 1.0 || *hz > 20.0) throw UsageError("--rotation-hz must be within 1..20");
      device.rotation_hz = *hz;
    }
    if (auto noise = command_line.DoubleValue("noise-m")) {
      if (*noise < 0.0 || *noise > 1.0) throw UsageError("--noise-m must be within 0..1");
      device.range_noise_m = *noise;
    }
    device.accessory_board = command_line.Flag("accessory-board");
    if (auto health = command_line.Value("health")) device.health = ParseHealth(*health);
    device.health_persists_after_reset = command_line.Flag("health-persists");
    std::vector<RplidarEmulatorFault> faults;
    for (const std::string& text : command_line.Values("fault")) faults.push_back(ParseFault(text));
    FaultSchedule schedule(FaultTimes(faults));

    EmulatorTransportOptions transport;
    if (auto port = command_line.IntValue("tcp")) {
      if (*port < 0 || *port > 65535) throw UsageError("--tcp must be a port 0..65535");
      transport.kind = EmulatorTransportOptions::Kind::kTcp;
      transport.tcp_port = static_cast<int>(*port);
      transport.bind_host = command_line.ValueOr("bind", "127.0.0.1");
    } else {
      if (command_line.Value("bind")) throw UsageError("--bind needs --tcp");
      transport.link_path = command_line.ValueOr("link", "");
    }

    RplidarEmulatorServer server(device, transport);
    const std::string endpoint = server.endpoint();
    LogInfo() << "RPLIDAR A2 emulator on " << endpoint
              << (device.accessory_board ? " (accessory board: motor by PWM)" : "");
    if (auto file = command_line.Value("endpoint-file")) WriteEndpointFile(*file, endpoint);
    server.Start();
    const auto start = std::chrono::steady_clock::now();
    while (!ShutdownRequested()) {
      const double elapsed_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      for (size_t index : schedule.TakeDue(elapsed_s)) Inject(faults[index], &server);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    server.Stop();
    const EmulatorServerStats stats = server.stats();
    LogInfo() << "stopped: " << stats.device.nodes_sent << " nodes, "
              << stats.device.capsules_sent << " capsules, " << stats.device.resets
              << " resets, " << stats.disconnects << " disconnects; scan "
              << (stats.device.scanning ? "running" : "stopped") << ", motor "
              << (stats.device.motor_running ? "running" : "stopped");
    return 0;  // the server's pty device removes its link when it goes
  });
}
