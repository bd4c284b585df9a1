// What the checks before decoding cost (slammtt::Decode against lcm-gen's decoder alone), and
// what they save on a corrupt count. Figures: docs/decoding.md.
//   build-*/bin/bench_message_decode --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "runtime/lcm_io.h"
#include "runtime/message_checks.h"

namespace slammtt {
namespace {

// An RPLIDAR A2 revolution: about 0.5 degree steps at 10 Hz in express mode.
slammtt_msgs::laser_scan_t Scan(int beams) {
  slammtt_msgs::laser_scan_t scan{};
  scan.utime = 1700000000000000;
  scan.range_min_m = 0.15f;
  scan.range_max_m = 12.0f;
  scan.num_beams = beams;
  for (int k = 0; k < beams; ++k) {
    scan.angle_rad.push_back(0.0087f * static_cast<float>(k));
    scan.range_m.push_back(1.0f + 0.01f * static_cast<float>(k % 300));
    scan.intensity.push_back(47.0f);
    scan.valid.push_back(1);
  }
  return scan;
}

slammtt_msgs::tracks_t Tracks(int n) {
  slammtt_msgs::tracks_t tracks{};
  tracks.utime = 1700000000000000;
  tracks.num_tracks = n;
  tracks.tracks.resize(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) tracks.tracks[static_cast<size_t>(k)].id = k;
  return tracks;
}

// The estimator's timing message: a dozen sub-stages and a few counters.
slammtt_msgs::stage_timing_t Timing() {
  slammtt_msgs::stage_timing_t timing{};
  timing.stage = "estimator";
  for (const char* name : {"predict", "gating", "level1", "ransac", "level3", "prune",
                           "classify", "initialise", "publish", "map", "tracks", "status"}) {
    timing.substage.push_back(name);
    timing.substage_ns.push_back(1000);
  }
  timing.num_substages = static_cast<int32_t>(timing.substage.size());
  timing.counter_name = {"features", "hypotheses", "objects", "landmarks"};
  timing.counter_value = {12, 300, 8, 20};
  timing.num_counters = 4;
  return timing;
}

template <class Msg>
void BM_Decode(benchmark::State& state, const Msg& message) {
  const std::vector<uint8_t> bytes = Encode(message);
  for (auto _ : state) {
    Msg decoded;
    benchmark::DoNotOptimize(Decode(bytes.data(), static_cast<int>(bytes.size()), &decoded));
    benchmark::DoNotOptimize(decoded);
  }
}

template <class Msg>
void BM_GeneratedDecoderAlone(benchmark::State& state, const Msg& message) {
  const std::vector<uint8_t> bytes = Encode(message);
  for (auto _ : state) {
    Msg decoded{};
    benchmark::DoNotOptimize(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())));
    benchmark::DoNotOptimize(decoded);
  }
}

template <class Msg>
void BM_CheckAlone(benchmark::State& state, const Msg& message) {
  const std::vector<uint8_t> bytes = Encode(message);
  for (auto _ : state) {
    benchmark::DoNotOptimize(PlausibleEncoding(static_cast<const Msg*>(nullptr), bytes.data(),
                                               static_cast<int>(bytes.size())));
  }
}

BENCHMARK_CAPTURE(BM_Decode, laser_scan_720, Scan(720));
BENCHMARK_CAPTURE(BM_GeneratedDecoderAlone, laser_scan_720, Scan(720));
BENCHMARK_CAPTURE(BM_CheckAlone, laser_scan_720, Scan(720));
BENCHMARK_CAPTURE(BM_Decode, tracks_20, Tracks(20));
BENCHMARK_CAPTURE(BM_GeneratedDecoderAlone, tracks_20, Tracks(20));
BENCHMARK_CAPTURE(BM_CheckAlone, tracks_20, Tracks(20));
BENCHMARK_CAPTURE(BM_Decode, stage_timing_12, Timing());
BENCHMARK_CAPTURE(BM_GeneratedDecoderAlone, stage_timing_12, Timing());
BENCHMARK_CAPTURE(BM_CheckAlone, stage_timing_12, Timing());

// A 3-feature FEATURES message whose count claims one million features: the generated decoder
// alone allocates and zeroes 1e6 feature_t (56 MB) before it finds the bytes missing; Decode
// rejects it from the count. (Larger claims cost proportionally more; this one is kept small
// enough to run on a shared machine.)
std::vector<uint8_t> CorruptFeatures() {
  slammtt_msgs::features_t features{};
  features.num_features = 3;
  features.features.resize(3);
  std::vector<uint8_t> bytes = Encode(features);
  const uint32_t claimed = 1000000;
  for (int k = 0; k < 4; ++k) {
    bytes[static_cast<size_t>(24 + k)] = static_cast<uint8_t>(claimed >> (24 - 8 * k));
  }
  return bytes;
}

void BM_DecodeCorruptCount(benchmark::State& state) {
  const std::vector<uint8_t> bytes = CorruptFeatures();
  for (auto _ : state) {
    slammtt_msgs::features_t decoded;
    benchmark::DoNotOptimize(Decode(bytes.data(), static_cast<int>(bytes.size()), &decoded));
  }
}
BENCHMARK(BM_DecodeCorruptCount);

void BM_GeneratedDecoderAloneCorruptCount(benchmark::State& state) {
  const std::vector<uint8_t> bytes = CorruptFeatures();
  for (auto _ : state) {
    slammtt_msgs::features_t decoded{};
    benchmark::DoNotOptimize(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())));
    benchmark::DoNotOptimize(decoded);
  }
}
BENCHMARK(BM_GeneratedDecoderAloneCorruptCount)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
