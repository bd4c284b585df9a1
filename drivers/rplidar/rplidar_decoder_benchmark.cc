// How fast the host side decodes what an A2 sends in one second: 2000 standard nodes
// (10 kB) or 125 express capsules of 32 samples (10.5 kB), fed in 64-byte chunks as a serial
// read would return them; and one revolution converted to beams.
#include <benchmark/benchmark.h>

#include <vector>

#include "drivers/rplidar/rplidar_beams.h"
#include "drivers/rplidar/rplidar_device_model.h"
#include "drivers/rplidar/rplidar_scan_decoder.h"

namespace slammtt {
namespace rplidar {
namespace {

std::vector<uint8_t> OneSecondOfScan(bool express) {
  RplidarDeviceModel model{RplidarDeviceOptions()};
  model.SetHostDtr(false, 0);
  const std::vector<uint8_t> request = express ? ExpressScanRequest() : ScanRequest();
  model.OnHostBytes(request.data(), request.size(), 0);
  model.TakeOutput(0);  // the descriptor
  std::vector<uint8_t> bytes;
  const int64_t start = RplidarDeviceOptions().spin_up_us;
  for (int64_t t = start; t <= start + 1000000; t += 1000) {
    const std::vector<uint8_t> chunk = model.TakeOutput(t);
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
  }
  return bytes;
}

template <class Decoder>
void DecodeOneSecond(benchmark::State& state, bool express) {
  const std::vector<uint8_t> bytes = OneSecondOfScan(express);
  std::vector<ScanSample> samples;
  samples.reserve(8192);
  for (auto _ : state) {
    Decoder decoder;
    samples.clear();
    for (size_t pos = 0; pos < bytes.size(); pos += 64) {
      decoder.Feed(bytes.data() + pos, std::min<size_t>(64, bytes.size() - pos), 0, &samples);
    }
    benchmark::DoNotOptimize(samples.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes.size()));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * samples.size()));
}

void BM_StandardDecoderOneSecond(benchmark::State& state) {
  DecodeOneSecond<StandardNodeDecoder>(state, false);
}
BENCHMARK(BM_StandardDecoderOneSecond);

void BM_ExpressDecoderOneSecond(benchmark::State& state) {
  DecodeOneSecond<ExpressCapsuleDecoder>(state, true);
}
BENCHMARK(BM_ExpressDecoderOneSecond);

void BM_ConvertRevolutionOf400Samples(benchmark::State& state) {
  std::vector<ScanSample> revolution(400);
  for (size_t i = 0; i < revolution.size(); ++i) {
    revolution[i].angle_q6 = static_cast<uint16_t>(i * 57);
    revolution[i].distance_q2 = static_cast<uint16_t>(4000 + i);
    revolution[i].quality = 47;
  }
  const BeamConversionOptions options;
  for (auto _ : state) {
    Beams beams = ConvertRevolution(revolution, options);
    benchmark::DoNotOptimize(beams.angle_rad.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * revolution.size()));
}
BENCHMARK(BM_ConvertRevolutionOf400Samples);

}  // namespace
}  // namespace rplidar
}  // namespace slammtt

BENCHMARK_MAIN();
