// build/bin/bench_estimator: per-scan cost of the estimator (docs/estimator.md).
//   BM_TypicalScan      the s1-crossing setting: 180-degree laser, ~20 landmarks and 5 movers in
//                       view, robot at 1.5 m/s, 8 Hz.
//   BM_Crowded          300 static landmarks and 30 movers all in view (360 degrees, 30 m), by
//                       update group size and per-scan budget of static-landmark updates
//                       (-1: the default EstimatorOptions::max_static_updates_per_scan, 0: none).
//   BM_UpdateBatch      one EKF update with every object observed, by update group size.
// Each scan benchmark first runs the world until the objects are classified (warm-up, not
// timed), then times consecutive scans of the same run; besides the mean it reports per-scan
// percentiles around ProcessScan only (the world's frames are generated beforehand):
// p50_ms, p99_ms, max_ms of the wall-clock time (steady clock) and cpu_p50_ms, cpu_p99_ms,
// cpu_max_ms of the thread's CPU time (CLOCK_THREAD_CPUTIME_ID), which a busy machine's
// preemptions do not inflate. Nearest-rank percentiles. The mean CPU time of each sub-stage
// (cpu_<substage>_ms) says where the time goes, and the accuracy over the timed scans says what
// a setting costs: ate_m (RMSE of the robot position against the world's truth), landmark_m
// (RMSE of the confirmed static landmarks at the last scan against their nearest true static
// point) and landmarks (how many there are).
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "estimator/ekf_update.h"
#include "estimator/estimator.h"
#include "estimator/testing/point_world.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::WorldFrame;
using testing::WorldObject;

double ThreadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Nearest-rank percentile of sorted values.
double Rank(const std::vector<double>& sorted, double q) {
  const size_t index = static_cast<size_t>(std::ceil(q * static_cast<double>(sorted.size()))) - 1;
  return sorted[std::min(index, sorted.size() - 1)];
}

// Thread CPU time of each sub-stage, summed over the scans it observed.
class SubstageClock : public StepObserver {
 public:
  void Start() { last_ms_ = ThreadCpuMs(); }
  void SubstageDone(Substage substage) override {
    const double now = ThreadCpuMs();
    total_ms_[static_cast<size_t>(substage)] += now - last_ms_;
    last_ms_ = now;
  }
  double total_ms(Substage substage) const { return total_ms_[static_cast<size_t>(substage)]; }

 private:
  double last_ms_ = 0.0;
  std::array<double, 6> total_ms_{};
};

// RMSE of the confirmed static landmarks against their nearest true static point.
double LandmarkRmse(const ScanResult& result, const WorldFrame& frame, int* count) {
  double sum = 0.0;
  *count = 0;
  for (const ObjectEstimate& e : result.objects) {
    if (e.object_class != ObjectClass::kStatic || !e.confirmed) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const testing::TruthObject& t : frame.objects) {
      if (!t.mover) nearest = std::min(nearest, (t.position_m - e.position).squaredNorm());
    }
    sum += nearest;
    ++*count;
  }
  return *count > 0 ? std::sqrt(sum / *count) : 0.0;
}

void RunScans(benchmark::State& state, const PointWorldOptions& world_options,
              const testing::RobotCommand& command, const std::vector<WorldObject>& objects,
              int warmup_scans, int timed_scans, const EstimatorOptions& options) {
  PointWorld world(world_options, command, objects);
  std::vector<WorldFrame> frames;
  for (int k = 0; k < warmup_scans + timed_scans; ++k) frames.push_back(world.Next());
  std::vector<double> durations_ms;
  std::vector<double> cpu_ms;
  size_t objects_total = 0;
  SubstageClock clock;
  std::array<double, 4> updates{};  // level 1, 2, 3, skipped by the budget
  double squared_pose_error = 0.0;
  double landmark_rmse = 0.0;
  int landmarks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Estimator estimator(options);
    std::mt19937_64 rng(1);
    for (int k = 0; k < warmup_scans; ++k) {
      for (const OdometryReading& r : frames[static_cast<size_t>(k)].odometry) estimator.AddOdometry(r);
      estimator.ProcessScan(frames[static_cast<size_t>(k)].scan, &rng);
    }
    state.ResumeTiming();
    for (int k = warmup_scans; k < warmup_scans + timed_scans; ++k) {
      const WorldFrame& frame = frames[static_cast<size_t>(k)];
      const double cpu_start = ThreadCpuMs();
      const auto start = std::chrono::steady_clock::now();
      for (const OdometryReading& r : frame.odometry) estimator.AddOdometry(r);
      clock.Start();
      const ScanResult result = estimator.ProcessScan(frame.scan, &rng, &clock);
      const auto end = std::chrono::steady_clock::now();
      cpu_ms.push_back(ThreadCpuMs() - cpu_start);
      durations_ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
      objects_total += result.objects.size();
      benchmark::DoNotOptimize(result.pose);
      updates[0] += result.counts.level1_updates;
      updates[1] += result.counts.level2_updates;
      updates[2] += result.counts.level3_updates;
      updates[3] += result.counts.static_updates_skipped;
      squared_pose_error += (result.pose.head<2>() - frame.true_pose.head<2>()).squaredNorm();
      if (k + 1 == warmup_scans + timed_scans) {
        landmark_rmse = LandmarkRmse(result, frame, &landmarks);
      }
    }
  }
  std::sort(durations_ms.begin(), durations_ms.end());
  std::sort(cpu_ms.begin(), cpu_ms.end());
  state.counters["scans"] = static_cast<double>(durations_ms.size());
  state.counters["objects"] =
      static_cast<double>(objects_total) / static_cast<double>(durations_ms.size());
  state.counters["p50_ms"] = Rank(durations_ms, 0.5);
  state.counters["p99_ms"] = Rank(durations_ms, 0.99);
  state.counters["max_ms"] = durations_ms.back();
  state.counters["cpu_p50_ms"] = Rank(cpu_ms, 0.5);
  state.counters["cpu_p99_ms"] = Rank(cpu_ms, 0.99);
  state.counters["cpu_max_ms"] = cpu_ms.back();
  const double scans = static_cast<double>(cpu_ms.size());
  for (Substage s : {Substage::kPredict, Substage::kGating, Substage::kLevel1, Substage::kRansac,
                     Substage::kLevel23, Substage::kTrackManagement}) {
    state.counters[std::string("cpu_") + SubstageName(s) + "_ms"] = clock.total_ms(s) / scans;
  }
  state.counters["level1_updates"] = updates[0] / scans;
  state.counters["level2_updates"] = updates[1] / scans;
  state.counters["level3_updates"] = updates[2] / scans;
  state.counters["skipped_updates"] = updates[3] / scans;
  state.counters["ate_m"] = std::sqrt(squared_pose_error / scans);
  state.counters["landmark_m"] = landmark_rmse;
  state.counters["landmarks"] = landmarks;
  state.SetItemsProcessed(static_cast<int64_t>(durations_ms.size()));
}

void BM_TypicalScan(benchmark::State& state) {
  PointWorldOptions world_options;  // 180 degrees, 30 m, 8 Hz, 0.2 m / 2 degrees
  world_options.sensor.forward_m = 0.1;
  std::vector<WorldObject> objects = testing::CrowdedScene(60, 0, 40.0, 7);
  for (int k = 0; k < 5; ++k) {
    WorldObject mover;
    mover.id = 1000 + k;
    mover.mover = true;
    mover.start_m = Eigen::Vector2d(8.0 + 3.0 * k, -6.0 + 2.5 * k);
    mover.segments.push_back({1e18, Eigen::Vector2d(-0.3 + 0.15 * k, 0.6 - 0.3 * k)});
    objects.push_back(mover);
  }
  EstimatorOptions options;
  options.sensor = world_options.sensor;
  options.field_of_view_rad = world_options.field_of_view_rad;
  RunScans(state, world_options,
           [](double t) { return Eigen::Vector2d(1.5, 0.2 * std::sin(0.1 * t)); }, objects, 80,
           400, options);
}
BENCHMARK(BM_TypicalScan)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_Crowded(benchmark::State& state) {
  PointWorldOptions world_options;
  world_options.field_of_view_rad = 2.0 * M_PI;
  world_options.scan_period_s = 0.1;
  const std::vector<WorldObject> objects =
      testing::CrowdedScene(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)),
                            25.0, 3);
  EstimatorOptions options;
  options.field_of_view_rad = world_options.field_of_view_rad;
  options.max_objects = 1000;
  options.update_group_size = static_cast<int>(state.range(2));
  if (state.range(3) >= 0) {
    options.max_static_updates_per_scan = static_cast<int>(state.range(3));
  }
  // 150 scans (15 s) of warm-up: the landmarks are static and the movers moving by then.
  RunScans(state, world_options, [](double) { return Eigen::Vector2d(0.25, 0.05); }, objects,
           150, 100, options);
}
BENCHMARK(BM_Crowded)
    ->Args({300, 30, 32, -1})
    ->Args({300, 30, 32, 0})
    ->Args({300, 30, 32, 120})
    ->Args({300, 30, 32, 80})
    ->Args({300, 30, 32, 60})
    ->Args({300, 30, 32, 50})
    ->Args({300, 30, 32, 40})
    ->Args({100, 10, 32, -1})
    ->Args({100, 10, 32, 0})
    ->ArgNames({"landmarks", "movers", "group", "budget"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// One update with all n objects observed once, from a state with every object correlated.
void BM_UpdateBatch(benchmark::State& state) {
  const int objects = static_cast<int>(state.range(0));
  const int group = static_cast<int>(state.range(1));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uniform(-15.0, 15.0);
  SlamState base(Eigen::Vector3d::Zero(), 0.01 * Eigen::Matrix3d::Identity());
  Eigen::Matrix<double, 2, 3> g;
  g << 1.0, 0.0, 0.3, 0.0, 1.0, -0.2;
  std::vector<ObjectObservation> observations;
  for (int k = 0; k < objects; ++k) {
    Eigen::Vector2d p(uniform(rng), uniform(rng));
    if (p.norm() < 2.0) p += Eigen::Vector2d(3.0, 0.0);
    base.AddObject(p, g, 0.05 * Eigen::Matrix2d::Identity(), ObjectRecord{});
    ObjectObservation o;
    o.object = k;
    o.measurement.range_bearing = PredictRangeBearing(base.robot_pose(), p, SensorMount{}) +
                                  Eigen::Vector2d(0.05, 0.01);
    o.measurement.covariance = Eigen::Vector2d(0.04, 0.0012).asDiagonal();
    observations.push_back(o);
  }
  for (auto _ : state) {
    state.PauseTiming();
    SlamState s = base;
    state.ResumeTiming();
    ApplyObservations(observations, SensorMount{}, std::numeric_limits<double>::infinity(), group,
                      &s);
    benchmark::DoNotOptimize(s.mean().data());
  }
  state.counters["states"] = base.dim();
}
BENCHMARK(BM_UpdateBatch)
    ->Args({330, 8})
    ->Args({330, 32})
    ->Args({330, 128})
    ->ArgNames({"objects", "group"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slammtt

BENCHMARK_MAIN();
