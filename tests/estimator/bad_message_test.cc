// One bad message among good ones (issue 15, item 2): an absurd odometry reading, a utime that
// jumps back or far ahead once. Each probe runs a point world (20 posts, 3 walkers, the robot
// on an arc at 0.5 m/s; 80 scans at 8 Hz, 400 odometry readings at 40 Hz) twice, clean and with
// the one bad message, on seeds 1-5, and prints the figures: the ATE of the processed scans
// against the true poses, how many published poses and objects were not finite, restarts.
// The bad message must change nothing beyond itself: no NaN, no restart, ATE within 0.02 m of
// the clean run's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/testing/point_world.h"

namespace slammtt {
namespace {

using testing::PointWorld;
using testing::PointWorldOptions;
using testing::WorldFrame;

constexpr int kScans = 80;
constexpr int kFaultScan = 40;  // the bad message comes with this scan

// Changes what one frame delivers; called for every frame with its index.
using Fault = std::function<void(int frame, WorldFrame* delivered)>;

struct ProbeRun {
  double ate_m = 0.0;             // RMS position error over the processed scans
  int scans_processed = 0;
  int non_finite_outputs = 0;     // scans whose pose or any object was not finite
  EstimatorCounters counters;
};

bool Finite(const ScanResult& result) {
  if (!result.pose.allFinite() || !result.pose_covariance.allFinite()) return false;
  for (const ObjectEstimate& e : result.objects) {
    if (!e.position.allFinite() || !e.velocity.allFinite() || !e.covariance.allFinite()) {
      return false;
    }
  }
  return true;
}

ProbeRun RunProbe(uint64_t seed, const Fault& fault) {
  PointWorldOptions world_options;
  world_options.seed = seed;
  world_options.field_of_view_rad = 2.0 * M_PI;
  PointWorld world(world_options, [](double) { return Eigen::Vector2d(0.5, 0.1); },
                   testing::CrowdedScene(20, 3, 8.0, seed));
  EstimatorOptions options;
  Estimator estimator(options);
  std::mt19937_64 rng(seed);
  ProbeRun run;
  double squared_error = 0.0;
  for (int frame = 0; frame < kScans; ++frame) {
    WorldFrame delivered = world.Next();
    if (fault) fault(frame, &delivered);
    for (const OdometryReading& reading : delivered.odometry) estimator.AddOdometry(reading);
    const ScanResult result = estimator.ProcessScan(delivered.scan, &rng);
    if (!result.processed) continue;
    if (!Finite(result)) {
      ++run.non_finite_outputs;
      continue;
    }
    ++run.scans_processed;
    squared_error += (result.pose.head<2>() - delivered.true_pose.head<2>()).squaredNorm();
  }
  run.ate_m = run.scans_processed > 0 ? std::sqrt(squared_error / run.scans_processed)
                                      : std::numeric_limits<double>::infinity();
  run.counters = estimator.counters();
  return run;
}

// The probe on seeds 1-5: prints clean and faulty figures, checks the faulty run.
void ExpectHarmless(const std::string& name, const Fault& fault) {
  std::vector<double> added_m;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const ProbeRun clean = RunProbe(seed, nullptr);
    const ProbeRun faulty = RunProbe(seed, fault);
    std::printf("%s seed %d: ATE clean %.4f m, with the bad message %.4f m; scans %d / %d; "
                "non-finite outputs %d; restarts %lld; odometry_rejected %lld\n",
                name.c_str(), static_cast<int>(seed), clean.ate_m, faulty.ate_m,
                faulty.scans_processed, clean.scans_processed, faulty.non_finite_outputs,
                static_cast<long long>(faulty.counters.restarts),
                static_cast<long long>(faulty.counters.odometry_rejected));
    SCOPED_TRACE(name + ", seed " + std::to_string(seed));
    EXPECT_EQ(faulty.non_finite_outputs, 0);
    EXPECT_EQ(faulty.counters.restarts, 0);
    EXPECT_GE(faulty.scans_processed, clean.scans_processed - 1);
    EXPECT_LE(faulty.ate_m, clean.ate_m + 0.02);
    added_m.push_back(faulty.ate_m - clean.ate_m);
  }
  std::sort(added_m.begin(), added_m.end());
  std::printf("%s: ATE added by the bad message, median %.4f m, worst %.4f m\n", name.c_str(),
              added_m[2], added_m[4]);
}

// Which odometry reading of the fault's frame is changed: the middle one.
OdometryReading* MiddleReading(WorldFrame* frame) {
  if (frame->odometry.empty()) return nullptr;
  return &frame->odometry[frame->odometry.size() / 2];
}

TEST(BadMessageTest, OneOdometryReadingAtXOf1e300) {
  ExpectHarmless("odometry x = 1e300", [](int frame, WorldFrame* delivered) {
    if (frame != kFaultScan) return;
    if (OdometryReading* r = MiddleReading(delivered)) r->pose(0) = 1e300;
  });
}

TEST(BadMessageTest, OneOdometryReadingFiftyMetresAway) {
  ExpectHarmless("odometry x + 50 m", [](int frame, WorldFrame* delivered) {
    if (frame != kFaultScan) return;
    if (OdometryReading* r = MiddleReading(delivered)) r->pose(0) += 50.0;
  });
}

TEST(BadMessageTest, OneOdometryReadingWithAnAbsurdSpeed) {
  ExpectHarmless("odometry 1e6 m/s", [](int frame, WorldFrame* delivered) {
    if (frame != kFaultScan) return;
    if (OdometryReading* r = MiddleReading(delivered)) r->linear_mps = 1e6;
  });
}

TEST(BadMessageTest, OneOdometryReadingAtUtimeMinusOne) {
  ExpectHarmless("odometry utime -1", [](int frame, WorldFrame* delivered) {
    if (frame != kFaultScan) return;
    if (OdometryReading* r = MiddleReading(delivered)) r->utime = -1;
  });
}

TEST(BadMessageTest, OneScanAMillionSecondsAhead) {
  ExpectHarmless("scan at +1e12 us", [](int frame, WorldFrame* delivered) {
    if (frame == kFaultScan) delivered->scan.utime += 1000000000000;
  });
}

TEST(BadMessageTest, OneOdometryReadingAMillionSecondsAhead) {
  ExpectHarmless("odometry at +1e12 us", [](int frame, WorldFrame* delivered) {
    if (frame != kFaultScan) return;
    if (OdometryReading* r = MiddleReading(delivered)) r->utime += 1000000000000;
  });
}

// Not a bad message: the base restarted and its odometry frame moved (500 m away, turned by
// 1 rad) from scan 40 on. Three consistent readings re-anchor the odometry; the motion across
// the jump (one reading interval) is extrapolated.
TEST(BadMessageTest, AnOdometryFrameThatJumpsForGoodIsReanchored) {
  const Eigen::Rotation2D<double> turn(1.0);
  const Eigen::Vector2d shift(500.0, -300.0);
  const Fault moved = [&](int frame, WorldFrame* delivered) {
    if (frame < kFaultScan) return;
    for (OdometryReading& r : delivered->odometry) {
      r.pose.head<2>() = turn * r.pose.head<2>() + shift;
      r.pose(2) += 1.0;
    }
  };
  ExpectHarmless("odometry frame moved", moved);
  const ProbeRun run = RunProbe(1, moved);
  EXPECT_EQ(run.counters.odometry_frame_jumps, 1);
  EXPECT_EQ(run.counters.odometry_rejected, 2);  // the two readings before the third agreed
  EXPECT_EQ(run.counters.odometry_processed, RunProbe(1, nullptr).counters.odometry_processed - 2);
}

}  // namespace
}  // namespace slammtt
