// What keeps a mover's track right when the sensor sees it badly or not at all: the "still"
// test judges only measured scans, and a feature cut by the edge of the field of view carries
// the uncertainty of the part that is cut off.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "estimator/estimator.h"
#include "estimator/motion_classifier.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;

// An UNDECIDED object whose estimate has not moved for 1.6 s, with a velocity estimate too
// uncertain to say anything: the displacement test decides.
struct StillCase {
  ObjectRecord record;
  Eigen::Vector2d position{0.05, 0.0};
  Eigen::Matrix2d position_cov = 0.01 * Eigen::Matrix2d::Identity();
  Eigen::Vector2d velocity{0.1, 0.0};
  Eigen::Matrix2d velocity_cov = 0.25 * Eigen::Matrix2d::Identity();
  int64_t now = 1600000;
  StillCase() {
    record.object_class = ObjectClass::kUndecided;
    record.class_change_utime = 0;
    RestartStillWindow(Eigen::Vector2d::Zero(), 0.01, 0, &record);
  }
  ClassChange Judge() {
    return ClassifyMover(position, position_cov, velocity, velocity_cov, now,
                         MotionClassifierOptions(), &record);
  }
};

TEST(StillTest, AnEstimateThatMovedLittleIsStillEvidenceOnlyWhenMeasured) {
  StillCase unmeasured;
  unmeasured.record.last_seen_utime = unmeasured.now - kSecond / 8;
  EXPECT_EQ(unmeasured.Judge(), ClassChange::kNone)
      << "an estimate that only coasted with its own velocity is no evidence of stillness";
  StillCase measured;
  measured.record.last_seen_utime = measured.now;
  EXPECT_EQ(measured.Judge(), ClassChange::kBecameStatic);
}

TEST(StillTest, TooLargeADisplacementIsNotStillEvenWhenMeasured) {
  StillCase moved;
  moved.record.last_seen_utime = moved.now;
  moved.position = Eigen::Vector2d(0.3, 0.0);  // 0.19 m/s over 1.6 s: above 0.15 m/s
  EXPECT_EQ(moved.Judge(), ClassChange::kNone);
}

// One feature per scan of a single object, from a robot standing at the origin with a
// 180-degree view, no odometry noise.
EstimatorOptions HalfViewOptions() {
  EstimatorOptions options;
  options.field_of_view_rad = M_PI;
  return options;
}

ScanInput OneFeature(int64_t utime, double range_m, double bearing_rad, double width_m) {
  ScanInput scan;
  scan.utime = utime;
  FeatureReading f;
  f.range_m = range_m;
  f.bearing_rad = bearing_rad;
  f.range_var_m2 = 0.03 * 0.03;
  f.bearing_var_rad2 = 0.01 * 0.01;
  f.width_m = width_m;
  scan.features.push_back(f);
  return scan;
}

TEST(EdgeOfViewTest, FeaturesReachingTheEdgeAreCountedOthersAreNot) {
  Estimator estimator(HalfViewOptions());
  std::mt19937_64 rng(1);
  // 2 m away at -89 degrees, 0.15 m wide: its extent reaches past -90 + 1 degrees.
  ScanResult edge = estimator.ProcessScan(OneFeature(1, 2.0, -89.0 * M_PI / 180.0, 0.15), &rng);
  EXPECT_EQ(edge.counts.features_at_edge_of_view, 1);
  // 2 m away at -80 degrees: well inside.
  ScanResult inside =
      estimator.ProcessScan(OneFeature(2, 2.0, -80.0 * M_PI / 180.0, 0.15), &rng);
  EXPECT_EQ(inside.counts.features_at_edge_of_view, 0);
  // A full view has no edge.
  EstimatorOptions full = HalfViewOptions();
  full.field_of_view_rad = 2.0 * M_PI;
  Estimator all_round(full);
  ScanResult none = all_round.ProcessScan(OneFeature(1, 2.0, -89.0 * M_PI / 180.0, 0.15), &rng);
  EXPECT_EQ(none.counts.features_at_edge_of_view, 0);
}

// A walker (radius 0.25 m) 2 m to the right of a robot that stands still (exact odometry,
// two posts in view) walks straight at 1.2 m/s out of the 180-degree view at bearing -90
// degrees. On its last scans the edge cuts it: the feature is the visible part's centre, up to
// 0.25 m inside the view. Without the edge's uncertainty that offset turns into a velocity error
// of up to 0.25 m / 0.125 s = 2 m/s (a manoeuvre's velocity jump absorbs it); with it, the
// track keeps about its velocity. Returns the velocity error after the last scan in view.
double VelocityErrorAfterLeavingTheView(double edge_sigma_m) {
  EstimatorOptions options = HalfViewOptions();
  options.edge_of_view_sigma_m = edge_sigma_m;
  Estimator estimator(options);
  std::mt19937_64 rng(3);
  std::mt19937_64 noise(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double dt = 0.125;
  const double radius = 0.25;
  const Eigen::Vector2d velocity(-1.2, 0.0);
  const Eigen::Vector2d start(3.0, -2.0);
  const Eigen::Vector2d posts[2] = {{6.0, 1.0}, {4.0, -4.0}};
  ScanResult last;
  for (int k = 0;; ++k) {
    const int64_t utime = 1 + k * kSecond / 8;
    OdometryReading standing;
    standing.utime = utime;
    estimator.AddOdometry(standing);
    const Eigen::Vector2d p = start + velocity * (k * dt);
    const double r = p.norm();
    const double b = std::atan2(p.y(), p.x());
    const double a = std::asin(radius / r);
    if (b + a < -0.5 * M_PI) break;  // wholly out of view
    const double lo = std::max(b - a, -0.5 * M_PI);  // the visible part
    const double hi = b + a;
    ScanInput scan = OneFeature(utime, r + 0.02 * unit(noise),
                                0.5 * (lo + hi) + 0.005 * unit(noise),
                                2.0 * r * std::sin(0.5 * (hi - lo)));
    for (const Eigen::Vector2d& post : posts) {
      scan.features.push_back(OneFeature(utime, post.norm() + 0.02 * unit(noise),
                                         std::atan2(post.y(), post.x()) + 0.005 * unit(noise),
                                         0.3)
                                  .features[0]);
    }
    last = estimator.ProcessScan(scan, &rng);
  }
  for (const ObjectEstimate& o : last.objects) {
    if (o.object_class == ObjectClass::kStatic) continue;
    EXPECT_EQ(o.object_class, ObjectClass::kMoving);
    return (o.velocity - velocity).norm();
  }
  ADD_FAILURE() << "no track of the walker";
  return 1e9;
}

TEST(EdgeOfViewTest, AWalkerCutByTheEdgeKeepsItsVelocity) {
  const double without = VelocityErrorAfterLeavingTheView(0.0);
  const double with = VelocityErrorAfterLeavingTheView(0.3);
  std::cout << "velocity error after the cut scan: " << without << " m/s without, " << with
            << " m/s with the edge's uncertainty\n";
  EXPECT_GT(without, 0.5);
  EXPECT_LT(with, 0.2);
}

}  // namespace
}  // namespace slammtt
