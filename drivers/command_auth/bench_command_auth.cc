// What authenticating a VELOCITY_COMMAND costs: signing (a base station, 10 Hz) and checking
// (slammtt-p3dx, once per command received, refused ones included).
#include <benchmark/benchmark.h>

#include "drivers/command_auth/command_signature.h"

namespace slammtt {
namespace {

constexpr int64_t kNow = 1700000000000000;

CommandKey BenchKey() {
  CommandKey key{};
  for (size_t k = 0; k < key.size(); ++k) key[k] = static_cast<uint8_t>(k * 13 + 5);
  return key;
}

void BM_SignCommand(benchmark::State& state) {
  VelocityCommandSigner signer(BenchKey(), "VELOCITY_COMMAND", 1);
  slammtt_msgs::velocity_command_t command{};
  command.utime = kNow;
  command.linear_mps = 0.3;
  for (auto _ : state) {
    signer.Sign(&command);
    benchmark::DoNotOptimize(command.tag[0]);
  }
}
BENCHMARK(BM_SignCommand);

// An accepted command: tag, window, counter, remembered.
void BM_CheckSignedCommand(benchmark::State& state) {
  VelocityCommandSigner signer(BenchKey(), "VELOCITY_COMMAND", 1);
  VelocityCommandVerifier verifier(BenchKey(), "VELOCITY_COMMAND");
  slammtt_msgs::velocity_command_t command{};
  command.utime = kNow;
  for (auto _ : state) {
    state.PauseTiming();
    signer.Sign(&command);
    state.ResumeTiming();
    benchmark::DoNotOptimize(verifier.Check(command, kNow));
  }
}
BENCHMARK(BM_CheckSignedCommand);

// A flood of unsigned commands costs one HMAC each.
void BM_CheckUnsignedCommand(benchmark::State& state) {
  VelocityCommandVerifier verifier(BenchKey(), "VELOCITY_COMMAND");
  slammtt_msgs::velocity_command_t command{};
  command.utime = kNow;
  command.linear_mps = 0.4;
  for (auto _ : state) benchmark::DoNotOptimize(verifier.Check(command, kNow));
}
BENCHMARK(BM_CheckUnsignedCommand);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
