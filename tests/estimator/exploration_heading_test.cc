// The heading of an EKF-SLAM exploration (issue 14, docs/smoother.md "What keeps the filter's
// heading sigma flat on the large loop"): a filter that sees only landmarks it initialised itself
// cannot learn its absolute heading, so nothing in the prediction, the initialisation of new
// landmarks, the update or the window's archiving may give it any. Library level, association
// given, no classifier: what the estimator's core does with its covariance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "estimator/ekf_prediction.h"
#include "estimator/ekf_update.h"
#include "estimator/landmark_window.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"
#include "tests/estimator/landmark_from_measurement.h"

namespace slammtt {
namespace {

// The large loop's odometry model (the estimator's defaults): 1e-4 m^2 and rad^2 per metre.
Eigen::Matrix2d OdometryCovariance(double step_m) {
  return Eigen::Vector2d(1e-4 * step_m, 1e-4 * step_m).asDiagonal();
}

ObjectRecord ConfirmedStaticLandmark(int64_t id) {
  ObjectRecord record;
  record.id = id;
  record.confirmed = true;
  record.object_class = ObjectClass::kStatic;
  record.kind = ObjectKind::kOther;
  return record;
}

struct Exploration {
  std::vector<double> heading_variance;  // after every step
  std::vector<double> heading_error_rad;
  int archived = 0;
};

// A robot drives straight along x at 0.125 m per step past posts 1 m apart, alternately 3 m
// left and right of its path. Range sigma 0.2 m, bearing sigma 2 degrees (the large loop's
// features). Each post is initialised at its first sighting; with `reobserve`, it is measured
// again at every step while within `visible_m` ahead of the robot, else never again. Posts
// farther than the window's 12 m leave the state (LandmarkArchive::Archive). Association given.
// `first_estimates`: the first-estimate Jacobians of slam_state.h, else the standard EKF.
Exploration Explore(double length_m, double visible_m, bool reobserve, bool first_estimates,
                    uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const SensorMount mount{0.1, 0.0};
  const double step_m = 0.125;
  const Eigen::Matrix2d q = OdometryCovariance(step_m);
  const double bearing_sigma = 2.0 * M_PI / 180.0;
  const Eigen::Matrix2d r = Eigen::Vector2d(0.04, bearing_sigma * bearing_sigma).asDiagonal();
  std::vector<Eigen::Vector2d> posts;
  for (int k = 1; k <= static_cast<int>(length_m) + 20; ++k) {
    posts.emplace_back(static_cast<double>(k), k % 2 == 0 ? 3.0 : -3.0);
  }
  std::vector<int64_t> id_of(posts.size(), -1);
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();
  SlamState state(truth, Eigen::Matrix3d::Zero(), 0.0);
  state.set_first_estimate_jacobians(first_estimates);
  LandmarkWindowOptions window;
  window.radius_m = 12.0;
  window.reenter_radius_m = 12.0;
  LandmarkArchive archive;
  Exploration out;
  const int steps = static_cast<int>(length_m / step_m);
  for (int step = 0; step < steps; ++step) {
    truth = PredictRobotPose(truth, OdometryIncrement{step_m, 0.0});
    const OdometryIncrement measured{step_m + std::sqrt(q(0, 0)) * normal(rng),
                                     std::sqrt(q(1, 1)) * normal(rng)};
    RobotMotionAccumulator motion(state.robot_pose(), 0.0, 0.0);
    motion.Add(measured, q);
    ApplyRobotPrediction(motion.pose(), motion.jacobian(), motion.noise(), &state);

    std::vector<ObjectObservation> observations;
    for (size_t i = 0; i < posts.size(); ++i) {
      const Eigen::Vector2d true_range_bearing = PredictRangeBearing(truth, posts[i], mount);
      if (true_range_bearing(0) > visible_m || std::abs(true_range_bearing(1)) > M_PI / 2) {
        continue;
      }
      PointMeasurement z;
      z.range_bearing =
          true_range_bearing + Eigen::Vector2d(0.2 * normal(rng), bearing_sigma * normal(rng));
      z.covariance = r;
      if (id_of[i] < 0) {
        id_of[i] = static_cast<int64_t>(i);
        AddLandmarkFromMeasurement(z, mount, ConfirmedStaticLandmark(id_of[i]), &state);
        continue;
      }
      if (!reobserve) continue;
      for (int k = 0; k < state.num_objects(); ++k) {
        if (state.object(k).record.id == id_of[i]) observations.push_back({k, z});
      }
    }
    ApplyObservations(observations, mount, std::numeric_limits<double>::infinity(), 32, &state);
    out.archived += archive.Archive(window, &state);
    out.heading_variance.push_back(state.robot_covariance()(2, 2));
    out.heading_error_rad.push_back(state.robot_pose()(2) - truth(2));
  }
  return out;
}

// Odometry alone: the heading variance after n steps of the same model.
double OdometryOnlyHeadingVariance(int steps) {
  return steps * OdometryCovariance(0.125)(1, 1);
}

// Landmarks seen once give no information: their initialisation must be correlated with the
// pose exactly (P_xr G^T), and their leaving (the window) must be a marginalisation. The
// heading variance is then that of odometry alone, to rounding.
TEST(ExplorationHeadingTest, LandmarksSeenOnceGiveTheHeadingNoInformation) {
  for (bool first_estimates : {false, true}) {
    const Exploration e = Explore(60.0, 8.0, /*reobserve=*/false, first_estimates, 1);
    EXPECT_GT(e.archived, 20);  // the window's marginalisation was exercised
    for (size_t k = 0; k < e.heading_variance.size(); k += 40) {
      const double odometry_only = OdometryOnlyHeadingVariance(static_cast<int>(k) + 1);
      EXPECT_NEAR(e.heading_variance[k], odometry_only, 1e-9 * odometry_only) << "step " << k;
    }
  }
}

// Landmarks seen again and again, then left behind: the heading is held relative to the local
// map, and the local map's heading is handed on from landmarks that leave to landmarks that
// arrive with a little loss each time. So the heading variance of the exploration grows (it
// can never fall: nothing absolute is seen), and the filter's heading errors stay within its
// sigma (NEES over seeds). The standard EKF fails this: its heading sigma stops growing at
// about 2.1 degrees after 140 m on every seed (2.14 -> 2.09 degrees from 160 to 220 m on seed
// 1; seed 2's heading error reaches 5.9 degrees, 2.8 sigma), the inconsistency that first-
// estimate Jacobians remove.
TEST(ExplorationHeadingTest, TheHeadingVarianceOfAnExplorationGrows) {
  const double length_m = 240.0;
  const int steps = static_cast<int>(length_m / 0.125);
  double nees_sum = 0.0;
  int nees_count = 0;
  for (uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u}) {
    const Exploration e = Explore(length_m, 6.0, /*reobserve=*/true, /*first_estimates=*/true, seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_EQ(static_cast<int>(e.heading_variance.size()), steps);
    // Sampled every 20 m from 40 m on (the first posts, seen from the exactly known start,
    // are gone by then): growing at each sample, and by a lot over the exploration.
    double previous = 0.0;
    for (int k = 320; k < steps; k += 160) {
      EXPECT_GT(e.heading_variance[static_cast<size_t>(k)], previous) << "step " << k;
      previous = e.heading_variance[static_cast<size_t>(k)];
    }
    EXPECT_GT(e.heading_variance.back(), 2.0 * e.heading_variance[320]);
    // Far below odometry alone: the landmarks do hold the heading, relative to each other.
    EXPECT_LT(e.heading_variance.back(), 0.5 * OdometryOnlyHeadingVariance(steps));
    for (int k = 320; k < steps; k += 160) {
      const double error = e.heading_error_rad[static_cast<size_t>(k)];
      nees_sum += error * error / e.heading_variance[static_cast<size_t>(k)];
      ++nees_count;
    }
  }
  // A consistent filter's mean NEES is 1 (chi^2 of one dof); the samples of one run are
  // correlated, so the bound is loose: 2 (an over-confident filter pinning the heading at a
  // few times too small a sigma gives 5-20).
  EXPECT_LT(nees_sum / nees_count, 2.0);
}

}  // namespace
}  // namespace slammtt
