// Google Benchmarks of the synthetic world (docs/world.md quotes the figures):
//   BM_CastBeams/<beams>/<objects>: the ray caster, beams per second (items_per_second);
//   BM_CastBeamsWithWalls/<beams>/<segments>: the same with 30 circles and wall segments;
//   BM_SimulateScenario/<name>: a whole shipped scenario (120 s), simulated seconds per wall
//     second (items = simulated seconds), without encoding or writing the log.
//   build/bin/bench_world --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>

#include "tools/world/laser_model.h"
#include "tools/world/portable_random.h"
#include "tools/world/ray_caster.h"
#include "tools/world/scenario_loader.h"
#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

// `objects` circles of radius 0.2-0.5 m scattered 1-25 m around the sensor.
std::vector<Circle> ScatteredCircles(int objects) {
  std::mt19937_64 rng(42);
  std::vector<Circle> circles;
  for (int i = 0; i < objects; ++i) {
    const double range = UniformBetween(rng, 1.0, 25.0);
    const double angle = UniformBetween(rng, -M_PI, M_PI);
    circles.push_back(Circle{range * std::cos(angle), range * std::sin(angle),
                             UniformBetween(rng, 0.2, 0.5)});
  }
  return circles;
}

void BM_CastBeams(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  const std::vector<Circle> circles = ScatteredCircles(static_cast<int>(state.range(1)));
  LaserSpec laser;
  laser.fov_deg = 360.0;
  laser.resolution_deg = 360.0 / beams;
  const std::vector<double> angles = LaserBeamAngles(laser);
  int64_t hits = 0;
  for (auto _ : state) {
    const std::vector<BeamHit> result = CastBeams(Pose2D{0.3, -0.2, 0.1}, angles, circles, 30.0);
    hits += result[0].circle;
    benchmark::DoNotOptimize(result.data());
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * beams);
  state.counters["beams"] = beams;
  state.counters["objects"] = static_cast<double>(circles.size());
}
BENCHMARK(BM_CastBeams)
    ->Args({400, 30})
    ->Args({800, 30})
    ->Args({1600, 30})
    ->Args({8000, 30})
    ->Args({400, 100})
    ->Unit(benchmark::kMicrosecond);

// `segments` wall pieces 1-3 m long scattered 1-12 m around the sensor (as many as a furnished
// office has within range).
std::vector<Segment> ScatteredSegments(int segments) {
  std::mt19937_64 rng(43);
  std::vector<Segment> out;
  for (int i = 0; i < segments; ++i) {
    const double range = UniformBetween(rng, 1.0, 12.0);
    const double angle = UniformBetween(rng, -M_PI, M_PI);
    const double direction = UniformBetween(rng, -M_PI, M_PI);
    const double half = 0.5 * UniformBetween(rng, 1.0, 3.0);
    const double x = range * std::cos(angle);
    const double y = range * std::sin(angle);
    out.push_back(Segment{x - half * std::cos(direction), y - half * std::sin(direction),
                          x + half * std::cos(direction), y + half * std::sin(direction)});
  }
  return out;
}

void BM_CastBeamsWithWalls(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  const std::vector<Circle> circles = ScatteredCircles(30);
  const std::vector<Segment> segments = ScatteredSegments(static_cast<int>(state.range(1)));
  LaserSpec laser;
  laser.resolution_deg = 360.0 / beams;
  const std::vector<double> angles = LaserBeamAngles(laser);
  int64_t hits = 0;
  for (auto _ : state) {
    const std::vector<BeamHit> result =
        CastBeams(Pose2D{0.3, -0.2, 0.1}, angles, circles, segments, 30.0);
    hits += result[0].segment;
    benchmark::DoNotOptimize(result.data());
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * beams);
  state.counters["segments"] = static_cast<double>(segments.size());
}
BENCHMARK(BM_CastBeamsWithWalls)
    ->Args({400, 60})
    ->Args({769, 60})
    ->Args({400, 200})
    ->Unit(benchmark::kMicrosecond);

void BM_SimulateScenario(benchmark::State& state, const std::string& name) {
  const Scenario scenario =
      LoadScenario(std::string(SLAMMTT_WORLD_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml");
  for (auto _ : state) {
    WorldSimulator world(scenario, 7, scenario.output);
    int64_t events = 0;
    while (!world.Done()) {
      benchmark::DoNotOptimize(world.Next());
      ++events;
    }
    benchmark::DoNotOptimize(events);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * scenario.duration_s));
}
BENCHMARK_CAPTURE(BM_SimulateScenario, s1_crossing, std::string("s1-crossing"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateScenario, s2_lobby, std::string("s2-lobby"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateScenario, crowd_zara02, std::string("crowd-zara02"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateScenario, office, std::string("office"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateScenario, office_hokuyo, std::string("office-hokuyo"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateScenario, corridor, std::string("corridor"))
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
