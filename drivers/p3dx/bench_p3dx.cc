// Costs of the P3-DX receive path and the driver's command latency.
//
//   build/bin/bench_p3dx --benchmark_repetitions=5 --benchmark_report_aggregates_only
//   tests/support/netns-run build/bin/bench_p3dx --benchmark_filter=CommandLatency
//       --benchmark_repetitions=5   (one line)
//
// BM_ReceiveSip: one extended SIP (37 bytes) through the streaming decoder, the SIP parser and
// the odometry integrator, fed as the serial line delivers it (8-byte chunks).
// BM_CommandLatency: a VELOCITY_COMMAND published on LCM until the emulated robot (in this
// process, over TCP) has received the VEL it turns into, through a real slammtt-p3dx process;
// 200 commands, counters p50_ms, p95_ms, max_ms over them (nearest rank).
// Needs an LCM bus: run it under tests/support/netns-run (or on a host with a multicast route).
#include <benchmark/benchmark.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <fstream>
#include <memory>
#include <thread>

#include "drivers/command_auth/command_key.h"
#include "drivers/command_auth/command_signature.h"
#include "drivers/common/driver_clock.h"
#include "drivers/p3dx/p3dx_commands.h"
#include "drivers/p3dx/p3dx_emulator.h"
#include "drivers/p3dx/p3dx_odometry.h"
#include "drivers/p3dx/p3dx_packet.h"
#include "drivers/p3dx/p3dx_sip.h"
#include "runtime/lcm_io.h"
#include "slammtt_msgs/velocity_command_t.hpp"

extern char** environ;

namespace slammtt {
namespace {

void BM_ReceiveSip(benchmark::State& state) {
  std::vector<uint8_t> stream;
  for (int i = 0; i < 64; ++i) {
    P3dxStandardSip sip;
    sip.moving = true;
    sip.x_pos = static_cast<uint16_t>(1000 + 37 * i);
    sip.y_pos = static_cast<uint16_t>(2000 + 11 * i);
    sip.th_pos = static_cast<int16_t>(5 * i);
    sip.left_vel = 250;
    sip.right_vel = 260;
    sip.battery_decivolts = 125;
    sip.io = P3dxSipIo{};
    sip.battery_decivolts_x10 = 125;
    sip.charge_state = 0;
    sip.rot_vel_decideg_per_s = 16;
    sip.fault_flags = 0;
    const std::vector<uint8_t> packet = FrameP3dxPacket(EncodeP3dxStandardSip(sip));
    stream.insert(stream.end(), packet.begin(), packet.end());
  }
  P3dxPacketDecoder decoder;
  P3dxOdometryIntegrator odometry;
  double sink = 0.0;
  int64_t sips = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < stream.size(); i += 8) {
      decoder.Feed(stream.data() + i, std::min<size_t>(8, stream.size() - i));
      while (auto payload = decoder.Next()) {
        const P3dxSipParse parse = ParseP3dxStandardSip(*payload);
        sink += odometry.Update(parse.sip).x_m;
        ++sips;
      }
    }
  }
  benchmark::DoNotOptimize(sink);
  state.SetItemsProcessed(sips);
  state.counters["ns_per_sip"] = benchmark::Counter(
      static_cast<double>(sips), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ReceiveSip)->Unit(benchmark::kMicrosecond);

void BM_CommandLatency(benchmark::State& state) {
  std::unique_ptr<lcm::LCM> lcm;
  try {
    lcm = OpenLcm(kDefaultLcmUrl);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  P3dxEmulatorOptions options;
  options.use_pty = false;
  P3dxEmulator emulator(options);
  std::atomic<bool> stop{false};
  std::thread serve([&] { emulator.Run([&] { return stop.load(); }); });
  const std::string driver = std::string(SLAMMTT_BIN_DIR) + "/slammtt-p3dx";
  const std::string endpoint = emulator.Endpoint();
  // The driver moves the robot only for commands signed with its key (docs/robot.md): the
  // latency includes the tag check.
  char directory[] = "/tmp/bench-p3dx-XXXXXX";
  if (mkdtemp(directory) == nullptr) {
    stop = true;
    serve.join();
    state.SkipWithError("cannot make a temporary directory");
    return;
  }
  const std::string key_path = std::string(directory) + "/command.key";
  const std::string config_path = std::string(directory) + "/stack.yaml";
  const CommandKey key = NewCommandKey();
  WriteNewCommandKeyFile(key_path, key);
  std::ofstream(config_path) << "p3dx:\n  command_key_file: " << key_path << "\n";
  VelocityCommandSigner signer(key, "VELOCITY_COMMAND", NewSenderId());
  SystemDriverClock wall_clock;
  const char* argv[] = {driver.c_str(), "--config", config_path.c_str(), "--port",
                        endpoint.c_str(), "--quiet", nullptr};
  pid_t pid = -1;
  if (posix_spawn(&pid, driver.c_str(), nullptr, nullptr, const_cast<char**>(argv), environ) != 0) {
    stop = true;
    serve.join();
    state.SkipWithError("cannot start slammtt-p3dx");
    return;
  }
  // Wait for the running session: ENABLE received and a second SIP sent, so the driver has had
  // the first one (until then it is "opening" and holds commands back: the first measurement
  // would be the session start, up to one SIP cycle).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  auto running = [&] {
    return emulator.WithModel(
        [](P3dxRobotModel& m) { return m.motors_enabled() && m.sips_sent() >= 2; });
  };
  while (!running() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!running()) {
    kill(pid, SIGTERM);
    waitpid(pid, nullptr, 0);
    stop = true;
    serve.join();
    state.SkipWithError("slammtt-p3dx did not open a session within 10 s");
    return;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  int value_mmps = 100;
  std::vector<double> latencies_ms;
  for (auto _ : state) {
    value_mmps = value_mmps == 100 ? 200 : 100;  // a change, so the driver sends at once
    const size_t before = emulator.WithModel([](P3dxRobotModel& m) { return m.received().size(); });
    slammtt_msgs::velocity_command_t command{};
    command.linear_mps = value_mmps / 1000.0;
    const auto start = std::chrono::steady_clock::now();
    command.utime = wall_clock.NowUtime();
    signer.Sign(&command);
    lcm->publish("VELOCITY_COMMAND", &command);
    bool arrived = false;
    while (!arrived && std::chrono::steady_clock::now() - start < std::chrono::seconds(2)) {
      arrived = emulator.WithModel([&](P3dxRobotModel& m) {
        const auto& received = m.received();
        for (size_t i = before; i < received.size(); ++i) {
          if (received[i].command.number == p3dx_command::kVel &&
              received[i].command.value == value_mmps) {
            return true;
          }
        }
        return false;
      });
      if (!arrived) std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!arrived) {
      state.SkipWithError("the VEL never arrived");
      break;
    }
    state.SetIterationTime(seconds);
    latencies_ms.push_back(seconds * 1000.0);
    // Keep the command timeout from stopping the robot between iterations.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGTERM);
  waitpid(pid, nullptr, 0);
  unlink(key_path.c_str());
  unlink(config_path.c_str());
  rmdir(directory);
  if (!latencies_ms.empty()) {
    std::sort(latencies_ms.begin(), latencies_ms.end());
    auto percentile = [&](double p) {  // nearest rank
      const size_t rank = static_cast<size_t>(std::ceil(p * latencies_ms.size()));
      return latencies_ms[std::min(latencies_ms.size(), std::max<size_t>(rank, 1)) - 1];
    };
    state.counters["p50_ms"] = percentile(0.50);
    state.counters["p95_ms"] = percentile(0.95);
    state.counters["max_ms"] = latencies_ms.back();
  }
  stop = true;
  serve.join();
}
BENCHMARK(BM_CommandLatency)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(200);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
