// build/bin/bench_metrics: cost of the matching at the heart of the evaluation (docs/tools.md).
// Sizes: a scan of the crowd scenario holds tens of objects; 200 bounds a large map.
#include <benchmark/benchmark.h>

#include <random>

#include "tools/metrics/assignment.h"
#include "tools/metrics/clear_mot.h"
#include "tools/metrics/set_distance.h"

namespace slammtt {
namespace {

PointSet RandomPoints(std::mt19937_64* rng, int n) {
  std::uniform_real_distribution<double> coordinate(0.0, 20.0);
  PointSet points;
  for (int k = 0; k < n; ++k) points.emplace_back(coordinate(*rng), coordinate(*rng));
  return points;
}

void BM_Assignment(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> value(0.0, 10.0);
  Eigen::MatrixXd cost(n, n + n / 4);
  for (Eigen::Index i = 0; i < cost.rows(); ++i) {
    for (Eigen::Index j = 0; j < cost.cols(); ++j) {
      const double v = value(rng);
      cost(i, j) = v < 7.0 ? v : kForbiddenCost;
    }
  }
  for (auto _ : state) benchmark::DoNotOptimize(SolveMinCostAssignment(cost));
}
BENCHMARK(BM_Assignment)->Arg(5)->Arg(20)->Arg(50)->Arg(200);

void BM_OspaGospa(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937_64 rng(2);
  const PointSet truth = RandomPoints(&rng, n);
  PointSet estimate = truth;
  std::normal_distribution<double> noise(0.0, 0.3);
  for (Eigen::Vector2d& p : estimate) p += Eigen::Vector2d(noise(rng), noise(rng));
  estimate.pop_back();
  for (auto _ : state) {
    benchmark::DoNotOptimize(Ospa(truth, estimate, 1.0, 2.0));
    benchmark::DoNotOptimize(Gospa(truth, estimate, 1.0, 2.0, 2.0));
  }
}
BENCHMARK(BM_OspaGospa)->Arg(5)->Arg(30);

void BM_ClearMotFrame(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937_64 rng(3);
  const PointSet truth = RandomPoints(&rng, n);
  std::vector<IdentifiedPoint> objects;
  std::vector<IdentifiedPoint> tracks;
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int k = 0; k < n; ++k) {
    objects.push_back({k, truth[k]});
    tracks.push_back({100 + k, truth[k] + Eigen::Vector2d(noise(rng), noise(rng))});
  }
  ClearMotAccumulator acc(1.0);
  for (auto _ : state) benchmark::DoNotOptimize(acc.AddFrame(objects, tracks));
}
BENCHMARK(BM_ClearMotFrame)->Arg(5)->Arg(30);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
