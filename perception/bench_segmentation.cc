// Throughput of the segmentation on realistic 360-degree scans: a 12 m x 9 m room (walls) with
// 20 round objects (people 0.2-0.3 m, posts 0.05-0.15 m) seen from inside, 1 cm range noise,
// 400 / 800 / 1600 / 8000 beams. items_per_second is beams per second on one core.
//   build/bin/bench_segmentation --benchmark_repetitions=5 --benchmark_report_aggregates_only
// Variants: the three centre rules; an RPLIDAR-like revolution (clockwise as the A2 turns,
// angles corrected by 0-2 degrees per sample as in express mode, so neighbours swap; starting
// at an arbitrary angle; 1 % dropped beams); the beams shuffled (a worst case for the sort).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "perception/segmenter.h"

namespace slammtt {
namespace {

struct RoomScan {
  std::vector<float> angle_rad;
  std::vector<float> range_m;
  std::vector<int8_t> valid;
};

double RayToCircle(double ux, double uy, double cx, double cy, double radius) {
  const double along = cx * ux + cy * uy;
  const double across = -cx * uy + cy * ux;
  const double q = radius * radius - across * across;
  if (q < 0.0 || along <= 0.0) return -1.0;
  return along - std::sqrt(q);
}

// Sensor at (1, -0.5) in a room spanning x in [-6, 6], y in [-4.5, 4.5].
RoomScan MakeRoomScan(int beams, bool rplidar_like, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  struct Circle {
    double x, y, r;
  };
  std::vector<Circle> objects;
  while (objects.size() < 20) {
    const Circle c{-5.5 + 11.0 * unit(rng), -4.0 + 8.0 * unit(rng),
                   objects.size() % 3 == 0 ? 0.05 + 0.1 * unit(rng) : 0.2 + 0.1 * unit(rng)};
    if (std::hypot(c.x - 1.0, c.y + 0.5) > c.r + 0.5) objects.push_back(c);
  }
  const double sx = 1.0, sy = -0.5;
  const double spacing = 2.0 * M_PI / beams;
  const double start = rplidar_like ? 2.0 * M_PI * unit(rng) : 0.0;
  RoomScan scan;
  for (int i = 0; i < beams; ++i) {
    // The RPLIDAR turns clockwise seen from above: in our CCW frame its angles decrease; in
    // express mode each sample's angle is corrected by 0-2 degrees, so neighbours swap.
    double angle = rplidar_like ? start - spacing * i : spacing * i;
    if (rplidar_like) angle += 2.0 * M_PI / 180.0 * unit(rng);
    if (angle < 0.0) angle += 2.0 * M_PI;
    angle = std::fmod(angle, 2.0 * M_PI);
    const double ux = std::cos(angle), uy = std::sin(angle);
    double best = 1e9;
    // Walls.
    if (ux > 1e-12) best = std::min(best, (6.0 - sx) / ux);
    if (ux < -1e-12) best = std::min(best, (-6.0 - sx) / ux);
    if (uy > 1e-12) best = std::min(best, (4.5 - sy) / uy);
    if (uy < -1e-12) best = std::min(best, (-4.5 - sy) / uy);
    for (const Circle& c : objects) {
      const double r = RayToCircle(ux, uy, c.x - sx, c.y - sy, c.r);
      if (r > 0.0 && r < best) best = r;
    }
    const bool dropped = rplidar_like && unit(rng) < 0.01;
    scan.angle_rad.push_back(static_cast<float>(angle));
    scan.range_m.push_back(dropped ? 0.0f : static_cast<float>(best + noise(rng)));
    scan.valid.push_back(dropped ? 0 : 1);
  }
  return scan;
}

void Run(benchmark::State& state, CentreRule rule, bool rplidar_like, bool shuffled = false) {
  const int beams = static_cast<int>(state.range(0));
  RoomScan scan = MakeRoomScan(beams, rplidar_like, 7);
  if (shuffled) {  // beams in random order: the segmenter has to sort them
    std::mt19937_64 rng(11);
    for (size_t i = scan.angle_rad.size(); i > 1; --i) {
      const size_t j = static_cast<size_t>(rng() % i);
      std::swap(scan.angle_rad[i - 1], scan.angle_rad[j]);
      std::swap(scan.range_m[i - 1], scan.range_m[j]);
      std::swap(scan.valid[i - 1], scan.valid[j]);
    }
  }
  ScanView view = MakeScanView(scan.angle_rad, scan.range_m, scan.valid);
  view.range_min_m = 0.15;
  view.range_max_m = 12.0;
  SegmenterOptions options;
  options.centre_rule = rule;
  Segmenter segmenter(options);
  size_t features = 0;
  for (auto _ : state) {
    const std::vector<Feature>& result = segmenter.Segment(view);
    features = result.size();
    benchmark::DoNotOptimize(result.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * beams);
  state.counters["features"] = static_cast<double>(features);
  state.counters["sorted"] = segmenter.stats().beams_were_sorted ? 1.0 : 0.0;
  state.counters["reversed"] = segmenter.stats().beams_were_reversed ? 1.0 : 0.0;
}

void BM_Segment_CircleFit(benchmark::State& state) { Run(state, CentreRule::kCircleFit, false); }
void BM_Segment_RadiusCorrected(benchmark::State& state) {
  Run(state, CentreRule::kRadiusCorrected, false);
}
void BM_Segment_MiddlePoint(benchmark::State& state) {
  Run(state, CentreRule::kMiddlePoint, false);
}
void BM_Segment_CircleFit_RplidarLike(benchmark::State& state) {
  Run(state, CentreRule::kCircleFit, true);
}

void BM_Segment_CircleFit_Shuffled(benchmark::State& state) {
  Run(state, CentreRule::kCircleFit, false, true);
}

BENCHMARK(BM_Segment_CircleFit)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
BENCHMARK(BM_Segment_RadiusCorrected)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
BENCHMARK(BM_Segment_MiddlePoint)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
// An RPLIDAR A2 revolution has 400 (express) or 800 (boost) samples at 10 Hz.
BENCHMARK(BM_Segment_CircleFit_RplidarLike)->Arg(400)->Arg(800);
BENCHMARK(BM_Segment_CircleFit_Shuffled)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
