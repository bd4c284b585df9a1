// Throughput of the segmentation on realistic 360-degree scans: a 12 m x 9 m room (walls) with
// 20 round objects (people 0.2-0.3 m, posts 0.05-0.15 m) seen from inside, 1 cm range noise,
// 400 / 800 / 1600 / 8000 beams. items_per_second is beams per second on one core.
//   build/bin/bench_segmentation --benchmark_repetitions=5 --benchmark_report_aggregates_only
// BM_Cluster_PaperPipeline: Algorithm 1 alone (extract_lines and detect_people off).
// BM_PerceptionStage_OfficeRplidar: the whole perception of an office-like RPLIDAR scan, per
// scan thread-CPU percentiles (cpu_p50_ms, cpu_p99_ms, cpu_max_ms).
// Variants: the three centre rules; an RPLIDAR-like revolution (clockwise as the A2 turns,
// angles corrected by 0-2 degrees per sample as in express mode, so neighbours swap; starting
// at an arbitrary angle; 1 % dropped beams); the beams shuffled (a worst case for the sort).
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
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

// The clustering alone (Algorithm 1 with point features, as the paper): line extraction and
// people off.
void BM_Cluster_PaperPipeline(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  RoomScan scan = MakeRoomScan(beams, false, 7);
  ScanView view = MakeScanView(scan.angle_rad, scan.range_m, scan.valid);
  view.range_min_m = 0.15;
  view.range_max_m = 12.0;
  SegmenterOptions options;
  options.extract_lines = false;
  options.detect_people = false;
  Segmenter segmenter(options);
  for (auto _ : state) benchmark::DoNotOptimize(segmenter.Segment(view).data());
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * beams);
}

// Thread CPU time [ms].
double ThreadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// An office-like RPLIDAR revolution: 400 beams (0.9 degrees) in a 10 x 7 m room with an inner
// wall and a door, a desk, a chair on four thin legs and four people on two legs each, range
// noise 0.01 m + 0.5 %, beams clockwise and corrected by 0-2 degrees as in express mode. The
// whole perception stage (clustering, lines, point features with leg-likeness, people) per
// scan, 200 different scans, thread CPU time per scan: p50, p99 and max (nearest rank).
void BM_PerceptionStage_OfficeRplidar(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  struct Seg {
    double x0, y0, x1, y1;
  };
  const std::vector<Seg> walls = {{-5, -3.5, 5, -3.5}, {5, -3.5, 5, 3.5},   {5, 3.5, -5, 3.5},
                                  {-5, 3.5, -5, -3.5}, {1, -3.5, 1, -0.5},  {1, 0.5, 1, 3.5},
                                  {-3, 2, -1.6, 2},    {-1.6, 2, -1.6, 2.7}, {-1.6, 2.7, -3, 2.7},
                                  {-3, 2.7, -3, 2}};
  std::vector<RoomScan> scans;
  for (int k = 0; k < 200; ++k) {
    struct Circle {
      double x, y, r;
    };
    std::vector<Circle> circles = {{-2.5, 1.2, 0.02}, {-2.05, 1.2, 0.02}, {-2.5, 0.75, 0.02},
                                   {-2.05, 0.75, 0.02}};
    for (int p = 0; p < 4; ++p) {
      const double px = -4.0 + 8.0 * unit(rng), py = -3.0 + 6.0 * unit(rng);
      const double h = 2.0 * M_PI * unit(rng), stride = 0.5 * (unit(rng) - 0.5);
      for (double side : {1.0, -1.0}) {
        circles.push_back({px + side * (0.5 * stride * std::cos(h) - 0.1 * std::sin(h)),
                           py + side * (0.5 * stride * std::sin(h) + 0.1 * std::cos(h)), 0.06});
      }
    }
    const double sx = -0.5 + unit(rng), sy = -1.0 + 2.0 * unit(rng);
    const double start = 2.0 * M_PI * unit(rng);
    RoomScan scan;
    for (int i = 0; i < 400; ++i) {
      double angle = start - 2.0 * M_PI / 400 * i + 2.0 * M_PI / 180.0 * unit(rng);
      angle = std::fmod(angle + 4.0 * M_PI, 2.0 * M_PI);
      const double ux = std::cos(angle), uy = std::sin(angle);
      double best = 1e9;
      for (const Seg& w : walls) {
        const double ex = w.x1 - w.x0, ey = w.y1 - w.y0;
        const double den = ux * ey - uy * ex;
        if (std::abs(den) < 1e-12) continue;
        const double ax = w.x0 - sx, ay = w.y0 - sy;
        const double t = (ax * ey - ay * ex) / den, u = (ax * uy - ay * ux) / den;
        if (t > 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
      }
      for (const Circle& c : circles) {
        const double r = RayToCircle(ux, uy, c.x - sx, c.y - sy, c.r);
        if (r > 0.0) best = std::min(best, r);
      }
      const bool hit = best < 12.0;
      scan.angle_rad.push_back(static_cast<float>(angle));
      scan.range_m.push_back(
          hit ? static_cast<float>(best + (0.01 + 0.005 * best) * noise(rng)) : 0.0f);
      scan.valid.push_back(hit ? 1 : 0);
    }
    scans.push_back(std::move(scan));
  }
  Segmenter segmenter(SegmenterOptions{});
  std::vector<double> cpu_ms;
  double lines = 0.0, features = 0.0, people = 0.0;
  for (auto _ : state) {
    for (const RoomScan& scan : scans) {
      ScanView view = MakeScanView(scan.angle_rad, scan.range_m, scan.valid);
      view.range_min_m = 0.15;
      view.range_max_m = 12.0;
      const double start_ms = ThreadCpuMs();
      benchmark::DoNotOptimize(segmenter.Segment(view).data());
      cpu_ms.push_back(ThreadCpuMs() - start_ms);
      lines += static_cast<double>(segmenter.lines().size());
      features += static_cast<double>(segmenter.features().size());
      people += static_cast<double>(segmenter.people().size());
    }
  }
  std::sort(cpu_ms.begin(), cpu_ms.end());
  const auto rank = [&](double q) {
    const size_t i = static_cast<size_t>(std::ceil(q * static_cast<double>(cpu_ms.size()))) - 1;
    return cpu_ms[std::min(i, cpu_ms.size() - 1)];
  };
  const double n = static_cast<double>(cpu_ms.size());
  state.counters["cpu_p50_ms"] = rank(0.5);
  state.counters["cpu_p99_ms"] = rank(0.99);
  state.counters["cpu_max_ms"] = cpu_ms.back();
  state.counters["lines"] = lines / n;
  state.counters["features"] = features / n;
  state.counters["people"] = people / n;
  state.SetItemsProcessed(static_cast<int64_t>(cpu_ms.size()) * 400);
}

BENCHMARK(BM_Segment_CircleFit)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
BENCHMARK(BM_Cluster_PaperPipeline)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
BENCHMARK(BM_PerceptionStage_OfficeRplidar);
BENCHMARK(BM_Segment_RadiusCorrected)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
BENCHMARK(BM_Segment_MiddlePoint)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);
// An RPLIDAR A2 revolution has 400 (express) or 800 (boost) samples at 10 Hz.
BENCHMARK(BM_Segment_CircleFit_RplidarLike)->Arg(400)->Arg(800);
BENCHMARK(BM_Segment_CircleFit_Shuffled)->Arg(400)->Arg(800)->Arg(1600)->Arg(8000);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
