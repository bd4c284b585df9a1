// The odometry's heading drift state (slam_state.h, ekf_prediction.h): a robot whose odometry
// turns by a systematic b_true radians per metre (a larger right wheel, UMBmark's type-B
// error) circles a few landmarks; the EKF with the drift state recovers b_true within its 2
// sigma and holds the heading better than the same EKF without the state.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "estimator/angle.h"
#include "estimator/ekf_prediction.h"
#include "estimator/ekf_update.h"
#include "estimator/range_bearing_model.h"
#include "estimator/slam_state.h"
#include "tests/estimator/landmark_from_measurement.h"

namespace slammtt {
namespace {

struct DriveOutcome {
  double drift_rad_per_m = 0.0;        // final estimate of b
  double drift_sigma_rad_per_m = 0.0;  // its final standard deviation
  double max_heading_error_rad = 0.0;  // over the second half of the drive
  double rms_heading_error_rad = 0.0;  // over the second half of the drive
  double min_covariance_eigenvalue = 0.0;
  double max_asymmetry = 0.0;
};

enum class Path {
  kCircle,    // 3 laps of a circle of radius 6 m around 6 landmarks, all seen up to 10 m
  kCorridor,  // 64 m straight past landmarks 2 m apart, 3 m either side, each seen up to 6 m:
              // every landmark is left behind, as in exploration (or s3-no-static's movers)
};

// The robot drives at 0.08 m per 0.1 s step; range sigma 0.03 m, bearing sigma 0.01 rad.
// Odometry: the true increment with its rotation reduced by b_true * d (so truth = odometry +
// b_true * d) plus noise drawn from the increment covariance the filter assumes. Seeded: the
// same outcome on every run.
DriveOutcome Drive(Path path, double true_drift_rad_per_m, double prior_sigma_rad_per_m,
                   uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const SensorMount mount{0.2, 0.0};
  const double step_m = 0.08;
  const bool circle = path == Path::kCircle;
  const double radius_m = 6.0;
  const double visible_m = circle ? 10.0 : 6.0;
  const int steps = circle ? static_cast<int>(std::ceil(3.0 * 2.0 * M_PI * radius_m / step_m))
                           : static_cast<int>(64.0 / step_m);
  // Random odometry errors of 1 cm and 1 mrad per sqrt(m): well-inflated tyres on a floor,
  // where the systematic drift (9 mrad per metre below) is the larger error.
  const Eigen::Matrix2d odometry_covariance = Eigen::Vector2d(1e-4 * step_m, 1e-6 * step_m).asDiagonal();
  const Eigen::Matrix2d r = Eigen::Vector2d(0.03 * 0.03, 0.01 * 0.01).asDiagonal();
  std::vector<Eigen::Vector2d> landmarks;
  if (circle) {
    landmarks = {{0.0, 6.0}, {3.0, 4.0}, {-2.0, 8.0}, {1.0, 10.0}, {-4.0, 3.0}, {5.0, 9.0}};
  } else {
    for (int k = 0; k <= 34; ++k) landmarks.emplace_back(2.0 * k, k % 2 == 0 ? 3.0 : -3.0);
  }
  Eigen::Vector3d truth(0.0, 0.0, 0.0);  // on the circle centred at (0, 6), driving CCW
  SlamState state(truth, Eigen::Matrix3d::Zero(), prior_sigma_rad_per_m * prior_sigma_rad_per_m);
  std::vector<int> object_of(landmarks.size(), -1);
  DriveOutcome outcome;
  double sum_squares = 0.0;
  int counted = 0;
  for (int step = 0; step < steps; ++step) {
    const OdometryIncrement true_increment{step_m, circle ? step_m / radius_m : 0.0};
    truth = PredictRobotPose(truth, true_increment);
    OdometryIncrement measured{
        true_increment.distance_m + std::sqrt(odometry_covariance(0, 0)) * normal(rng),
        true_increment.rotation_rad - true_drift_rad_per_m * step_m +
            std::sqrt(odometry_covariance(1, 1)) * normal(rng)};
    RobotMotionAccumulator motion(state.robot_pose(), state.heading_drift_rad_per_m(), 0.0);
    motion.Add(measured, odometry_covariance);
    ApplyRobotPrediction(motion.pose(), motion.jacobian(), motion.noise(), &state);

    std::vector<ObjectObservation> observations;
    for (size_t i = 0; i < landmarks.size(); ++i) {
      const Eigen::Vector2d true_range_bearing = PredictRangeBearing(truth, landmarks[i], mount);
      if (true_range_bearing(0) > visible_m) continue;
      PointMeasurement z;
      z.range_bearing = true_range_bearing + Eigen::Vector2d(0.03 * normal(rng), 0.01 * normal(rng));
      z.covariance = r;
      if (object_of[i] < 0) {
        object_of[i] = AddLandmarkFromMeasurement(z, mount, ObjectRecord{}, &state);
        continue;
      }
      observations.push_back(ObjectObservation{object_of[i], z});
    }
    ApplyObservations(observations, mount, std::numeric_limits<double>::infinity(), 8, &state);
    if (step >= steps / 2) {
      const double error = std::abs(WrapAngle(state.robot_pose()(2) - truth(2)));
      outcome.max_heading_error_rad = std::max(outcome.max_heading_error_rad, error);
      sum_squares += error * error;
      ++counted;
    }
  }
  outcome.rms_heading_error_rad = std::sqrt(sum_squares / counted);
  outcome.drift_rad_per_m = state.heading_drift_rad_per_m();
  outcome.drift_sigma_rad_per_m = std::sqrt(state.heading_drift_variance());
  const Eigen::MatrixXd p = state.covariance();
  outcome.max_asymmetry = (p - p.transpose()).cwiseAbs().maxCoeff();
  outcome.min_covariance_eigenvalue =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  return outcome;
}

// A 0.3 % larger right wheel on a 0.33 m axle: the odometry turns 0.009 rad/m too far left.
constexpr double kTrueDrift_rad_per_m = -0.009;
constexpr double kPriorSigma_rad_per_m = 0.0075;  // the estimator's default (estimator.h)

TEST(HeadingDriftTest, ConvergesToTheOdometrysSystematicDrift) {
  for (Path path : {Path::kCircle, Path::kCorridor}) {
    for (uint64_t seed : {1u, 2u, 3u}) {
      const DriveOutcome o = Drive(path, kTrueDrift_rad_per_m, kPriorSigma_rad_per_m, seed);
      SCOPED_TRACE("path " + std::to_string(static_cast<int>(path)) + " seed " +
                   std::to_string(seed));
      EXPECT_LT(std::abs(o.drift_rad_per_m - kTrueDrift_rad_per_m), 2.0 * o.drift_sigma_rad_per_m)
          << "estimate " << o.drift_rad_per_m << " sigma " << o.drift_sigma_rad_per_m;
      // Informative: the posterior is far narrower than the prior and than the drift itself.
      EXPECT_LT(o.drift_sigma_rad_per_m, 0.3 * std::abs(kTrueDrift_rad_per_m));
      EXPECT_LT(o.max_asymmetry, 1e-15);
      EXPECT_GE(o.min_covariance_eigenvalue, -1e-12);
    }
  }
}

TEST(HeadingDriftTest, StaysNearZeroWhenTheOdometryHasNoDrift) {
  for (Path path : {Path::kCircle, Path::kCorridor}) {
    const DriveOutcome o = Drive(path, 0.0, kPriorSigma_rad_per_m, 4);
    EXPECT_LT(std::abs(o.drift_rad_per_m), 2.0 * o.drift_sigma_rad_per_m);
  }
}

// Where landmarks are left behind, the heading error of the filter without the state keeps
// growing with the uncorrected drift; with the state it stays bounded.
TEST(HeadingDriftTest, HoldsTheHeadingBetterThanTheFilterWithoutIt) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    const DriveOutcome with_state =
        Drive(Path::kCorridor, kTrueDrift_rad_per_m, kPriorSigma_rad_per_m, seed);
    const DriveOutcome without = Drive(Path::kCorridor, kTrueDrift_rad_per_m, 0.0, seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    // Off means off: b stays exactly zero with a zero prior and no random walk.
    EXPECT_EQ(without.drift_rad_per_m, 0.0);
    EXPECT_EQ(without.drift_sigma_rad_per_m, 0.0);
    EXPECT_LT(with_state.rms_heading_error_rad, 0.5 * without.rms_heading_error_rad)
        << with_state.rms_heading_error_rad << " vs " << without.rms_heading_error_rad;
    EXPECT_LT(with_state.max_heading_error_rad, 0.5 * without.max_heading_error_rad)
        << with_state.max_heading_error_rad << " vs " << without.max_heading_error_rad;
  }
}

}  // namespace
}  // namespace slammtt
