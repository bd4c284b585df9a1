// slammtt-sim-robot: one simulated robot behind both device emulators (simulated_robot.h): the
// P3-DX's and the RPLIDAR A2's byte protocols on pseudo-terminals or TCP ports, a scenario's
// world around them, and GROUND_TRUTH on the bus for every LASER_SCAN. docs/robot.md,
// "Without the robot".
//   slammtt-sim-robot --scenario office --seed 1 --p3dx-tcp 5101 --rplidar-tcp 5102
#include <cstdint>
#include <iostream>
#include <string>

#include "drivers/sim_robot/simulated_robot.h"
#include "runtime/command_line.h"
#include "runtime/event_loop.h"
#include "runtime/lcm_bus.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"
#include "tools/world/scenario_loader.h"

namespace slammtt {
namespace {

int TcpPort(const CommandLine& cl, const char* name) {
  const int64_t port = *cl.IntValue(name);
  if (port < 0 || port > 65535) throw UsageError(std::string("--") + name + ": port 0..65535");
  return static_cast<int>(port);
}

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-sim-robot", "--scenario NAME|PATH [options]",
                 "One simulated robot behind the P3-DX and RPLIDAR A2 emulators: the base's "
                 "motion (from the commands its driver sends) moves the robot of a scenario's "
                 "world, the laser measures that world from the robot's pose, the scenario's "
                 "people walk, and GROUND_TRUTH goes on the bus at every LASER_SCAN's utime. "
                 "Prints the two endpoints (base, then laser) on stdout.");
  AddStandardOptions(&cl);
  cl.AddOption("scenario", "NAME|PATH",
               "the world: a name from config/scenarios/ (office, corridor, ...) or a file");
  cl.AddOption("seed", "N", "seed of the people and the wheel slip (default 1)");
  cl.AddOption("p3dx-tcp", "PORT", "serve the base on this TCP port (default: a pty)");
  cl.AddOption("p3dx-link", "PATH", "publish the base's pty as this symlink");
  cl.AddOption("rplidar-tcp", "PORT", "serve the laser on this TCP port (default: a pty)");
  cl.AddOption("rplidar-link", "PATH", "publish the laser's pty as this symlink");
  cl.AddOption("bind", "HOST", "address the TCP ports listen on (default 127.0.0.1)");
  cl.AddOption("step-ms", "MS", "how often the world follows the base (default 5, 1..50)");
  if (!cl.Parse(argc, argv)) return 0;
  const ProcessSettings settings = LoadProcessSettings(cl);
  const auto scenario_arg = cl.Value("scenario");
  if (!scenario_arg) throw UsageError("--scenario is required (see --help)");
  const int64_t seed = cl.IntValue("seed").value_or(1);
  if (seed < 0) throw UsageError("--seed must be >= 0");

  SimulatedRobotOptions options;
  const std::string bind = cl.ValueOr("bind", "127.0.0.1");
  if (cl.Value("p3dx-tcp")) {
    if (cl.Value("p3dx-link")) throw UsageError("--p3dx-link applies to a pty, not to --p3dx-tcp");
    options.base.use_pty = false;
    options.base.tcp_port = TcpPort(cl, "p3dx-tcp");
    options.base.tcp_bind_host = bind;
  } else {
    options.base.pty_link = cl.ValueOr("p3dx-link", "");
  }
  if (cl.Value("rplidar-tcp")) {
    if (cl.Value("rplidar-link")) {
      throw UsageError("--rplidar-link applies to a pty, not to --rplidar-tcp");
    }
    options.laser_transport.kind = rplidar::EmulatorTransportOptions::Kind::kTcp;
    options.laser_transport.tcp_port = TcpPort(cl, "rplidar-tcp");
    options.laser_transport.bind_host = bind;
  } else {
    options.laser_transport.link_path = cl.ValueOr("rplidar-link", "");
  }
  if (auto step = cl.IntValue("step-ms")) {
    if (*step < 1 || *step > 50) throw UsageError("--step-ms must be within 1..50");
    options.step_ms = static_cast<int>(*step);
  }
  options.laser_scan_channel = settings.channels.Get("laser_scan");
  options.ground_truth_channel = settings.channels.Get("ground_truth");

  const std::string path =
      ResolveScenarioPath(*scenario_arg, ScenarioSearchRoots(SLAMMTT_SOURCE_ROOT));
  const Scenario scenario = LoadScenario(path);
  LcmBus bus(settings.lcm_url);
  SteadyMonotonicClock clock;
  EventLoop loop(&bus, &clock);
  SimulatedRobot robot(scenario, static_cast<uint64_t>(seed), options, &loop);
  std::cout << robot.base_endpoint() << "\n" << robot.laser_endpoint() << std::endl;
  LogInfo() << "scenario " << scenario.name << " seed " << seed << ": base on "
            << robot.base_endpoint() << ", laser on " << robot.laser_endpoint()
            << ", GROUND_TRUTH on " << options.ground_truth_channel;
  robot.Run([] { return ShutdownRequested(); });
  const SimulatedRobotStats stats = robot.stats();
  const RobotTruth truth = robot.robot();
  LogInfo() << "stopped: " << stats.truth_published << " GROUND_TRUTH published, "
            << stats.scans_outside_history << " scans without truth, " << stats.bad_scans
            << " bad scans; robot at x " << truth.pose.x_m << " m, y " << truth.pose.y_m
            << " m, heading " << truth.pose.heading_rad << " rad";
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-sim-robot", slammtt::Run);
}
