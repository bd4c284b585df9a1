// The motion of a robot without odometry from aligning consecutive scans (scan_alignment.h):
// a known motion recovered, walking legs and strays not followed, a single wall and a corridor
// leaving the unobserved direction at the guess with a large variance, the features taken from
// the scan as the robot sees them, and the pose-increment step of the prediction with its
// Jacobians checked numerically.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "common/angle.h"
#include "estimator/ekf_prediction.h"
#include "estimator/scan_alignment.h"
#include "tests/support/numerical_derivative.h"

namespace slammtt {
namespace {

// A point of the previous robot frame seen from the robot after `increment` (the inverse of the
// alignment's map: p_previous = R p + t).
Eigen::Vector2d SeenAfter(const Eigen::Vector3d& increment, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(-increment.z()) * (p - increment.head<2>());
}

AlignmentScan Moved(const AlignmentScan& reference, const Eigen::Vector3d& increment) {
  AlignmentScan scan;
  for (const Eigen::Vector2d& p : reference.points_m) {
    scan.points_m.push_back(SeenAfter(increment, p));
  }
  for (const AlignmentSegment& s : reference.segments) {
    scan.segments.push_back({SeenAfter(increment, s.from_m), SeenAfter(increment, s.to_m),
                             s.direction_var_rad2});
  }
  return scan;
}

// A room of 8 x 6 m around the robot, seen as four wall runs (shortened where a door or the
// view cuts them) and three posts.
AlignmentScan Room() {
  AlignmentScan room;
  room.segments = {{{-3.5, -2.8}, {3.8, -2.8}},
                   {{4.0, -2.5}, {4.0, 2.6}},
                   {{3.6, 3.0}, {0.5, 3.0}},
                   {{-4.0, 2.7}, {-4.0, -2.2}}};
  room.points_m = {{1.5, 1.0}, {-2.0, -1.2}, {2.5, -1.8}};
  return room;
}

Eigen::Matrix3d Prior(double position_sigma_m, double heading_sigma_rad) {
  return Eigen::Vector3d(position_sigma_m * position_sigma_m, position_sigma_m * position_sigma_m,
                         heading_sigma_rad * heading_sigma_rad)
      .asDiagonal();
}

TEST(ScanAlignmentTest, RecoversAKnownMotion) {
  const Eigen::Vector3d truth(0.08, -0.03, 0.05);
  AlignmentScan scan = Moved(Room(), truth);
  // Range noise of a laser: 1 cm on every end and point.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (Eigen::Vector2d& p : scan.points_m) p += Eigen::Vector2d(noise(rng), noise(rng));
  for (AlignmentSegment& s : scan.segments) {
    s.from_m += Eigen::Vector2d(noise(rng), noise(rng));
    s.to_m += Eigen::Vector2d(noise(rng), noise(rng));
  }
  const ScanAlignment a =
      AlignScans(Room(), scan, Eigen::Vector3d::Zero(), Prior(0.1, 0.1), ScanAlignmentOptions{});
  EXPECT_NEAR(a.increment.x(), truth.x(), 0.01);
  EXPECT_NEAR(a.increment.y(), truth.y(), 0.01);
  EXPECT_NEAR(a.increment.z(), truth.z(), 0.003);
  EXPECT_EQ(a.line_pairs, 4);
  EXPECT_EQ(a.point_pairs, 3);
  // Well observed everywhere: a few centimetres at most, far below the prior's 10 cm.
  EXPECT_LT(std::sqrt(a.covariance(0, 0)), 0.03);
  EXPECT_LT(std::sqrt(a.covariance(1, 1)), 0.03);
  EXPECT_LT(std::sqrt(a.covariance(2, 2)), 0.01);
}

TEST(ScanAlignmentTest, RecoversATurnThatBeganSinceThePreviousScan) {
  // 60 deg/s for 0.1 s since the previous scan, which went straight on: the guess is off by
  // 6 degrees, beyond match_angle, and the posts 4 m away by 40 cm, beyond match_m.
  const Eigen::Vector3d truth(0.03, 0.0, 0.105);
  const Eigen::Vector3d guess(0.03, 0.0, 0.0);
  const ScanAlignmentOptions options;
  const std::optional<double> turn = TurnFromLines(Room(), Moved(Room(), truth), 0.0, 0.03, options);
  ASSERT_TRUE(turn.has_value());
  EXPECT_NEAR(*turn, truth.z(), 1e-9);
  const ScanAlignment a = AlignScans(Room(), Moved(Room(), truth), guess, Prior(0.03, 0.1), options);
  EXPECT_NEAR(a.increment.x(), truth.x(), 3e-3);
  EXPECT_NEAR(a.increment.y(), truth.y(), 3e-3);
  EXPECT_NEAR(a.increment.z(), truth.z(), 2e-3);
  EXPECT_EQ(a.line_pairs, 4);
  // A scan of one short line does not vote (under kMinTurnVote_m of agreeing length).
  AlignmentScan stub;
  stub.segments = {{{1.0, 0.0}, {1.0, 0.5}}};
  EXPECT_FALSE(TurnFromLines(stub, stub, 0.0, 0.0, options).has_value());
}

TEST(ScanAlignmentTest, WalkingLegsAndStraysAreNotFollowed) {
  const Eigen::Vector3d truth(0.05, 0.02, -0.03);
  AlignmentScan reference = Room();
  // Two legs and a stray cluster of the previous scan...
  reference.points_m.push_back({1.0, -0.5});
  reference.points_m.push_back({1.2, -0.4});
  reference.points_m.push_back({-1.0, 2.0});
  AlignmentScan scan = Moved(reference, truth);
  // ... moved 15 cm (a walking person) and 25 cm (the stray, a wrong association).
  scan.points_m[3] += Eigen::Vector2d(0.15, 0.0);
  scan.points_m[4] += Eigen::Vector2d(0.0, 0.15);
  scan.points_m[5] += Eigen::Vector2d(-0.25, 0.0);
  const ScanAlignment a = AlignScans(reference, scan, Eigen::Vector3d::Zero(), Prior(0.1, 0.1),
                                     ScanAlignmentOptions{});
  EXPECT_NEAR(a.increment.x(), truth.x(), 0.005);
  EXPECT_NEAR(a.increment.y(), truth.y(), 0.005);
  EXPECT_NEAR(a.increment.z(), truth.z(), 0.002);
}

TEST(ScanAlignmentTest, ASingleWallLeavesTheMotionAlongItAtTheGuessWithItsVariance) {
  // A wall 2 m to the left, along x; the robot moved 10 cm along it, and 3 cm towards it.
  AlignmentScan wall;
  wall.segments = {{{-3.0, 2.0}, {3.0, 2.0}}};
  const Eigen::Vector3d truth(0.10, 0.03, 0.0);
  const Eigen::Vector3d guess(0.02, 0.0, 0.0);
  const Eigen::Matrix3d prior = Prior(0.05, 0.05);
  const ScanAlignmentOptions options;
  const ScanAlignment a = AlignScans(wall, Moved(wall, truth), guess, prior, options);
  // Across the wall and in heading: measured (the prior pulls the 3 cm by under 10 %).
  EXPECT_NEAR(a.increment.y(), truth.y(), 3e-3);
  EXPECT_NEAR(a.increment.z(), truth.z(), 1e-3);
  // Along it: the guess, not a value the residuals made up, with the guess's variance.
  EXPECT_NEAR(a.increment.x(), guess.x(), 1e-6);
  EXPECT_NEAR(a.covariance(0, 0), options.covariance_scale * prior(0, 0), 1e-9);
  EXPECT_LT(a.covariance(1, 1), 0.1 * a.covariance(0, 0));
  // The truth lies inside three sigmas of what the alignment says.
  EXPECT_LT(std::abs(a.increment.x() - truth.x()), 3.0 * std::sqrt(a.covariance(0, 0)));
}

TEST(ScanAlignmentTest, ACorridorWithoutFeaturesAlongItLeavesThatDirectionUnobserved) {
  AlignmentScan corridor;
  corridor.segments = {{{-4.0, 1.0}, {4.0, 1.0}}, {{4.0, -1.0}, {-4.0, -1.0}}};
  const Eigen::Vector3d truth(0.12, -0.02, 0.01);
  const ScanAlignmentOptions options;
  const Eigen::Matrix3d prior = Prior(0.05, 0.05);
  const Eigen::Vector3d guess(0.10, 0.0, 0.0);
  const ScanAlignment a = AlignScans(corridor, Moved(corridor, truth), guess, prior, options);
  EXPECT_NEAR(a.increment.y(), truth.y(), 3e-3);
  EXPECT_NEAR(a.increment.z(), truth.z(), 1e-3);
  EXPECT_NEAR(a.increment.x(), guess.x(), 1e-6);
  EXPECT_NEAR(a.covariance(0, 0), options.covariance_scale * prior(0, 0), 1e-9);
  // Two posts further along the corridor make the direction observed.
  corridor.points_m = {{3.0, 0.6}, {2.5, -0.7}};
  const ScanAlignment with_posts =
      AlignScans(corridor, Moved(corridor, truth), guess, prior, options);
  EXPECT_NEAR(with_posts.increment.x(), truth.x(), 5e-3);
  EXPECT_LT(with_posts.covariance(0, 0), 0.3 * a.covariance(0, 0));
}

TEST(ScanAlignmentTest, AShortNoisyRunAcrossACorridorFixesTheMotionAlongIt) {
  // The start of office: a corridor of two long walls and, 4 m ahead, a door jamb's face of
  // 0.42 m seen by 7 beams, whose fitted direction is 4.7 degrees uncertain; the next scan's fit
  // of it is 8 degrees off the previous one's (1.2 sigmas of the difference), beyond
  // match_angle.
  const double jamb_var = std::pow(4.7 * M_PI / 180.0, 2);
  AlignmentScan corridor;
  corridor.segments = {{{-1.0, 0.75}, {2.0, 0.75}, 1e-5},
                       {{-1.0, -0.75}, {1.0, -0.75}, 1e-5},
                       {{4.1, 1.0}, {4.1, 1.42}, jamb_var}};
  const Eigen::Vector3d truth(0.03, 0.0, 0.0);  // 0.3 m/s for 0.1 s
  AlignmentScan scan = Moved(corridor, truth);
  AlignmentSegment& jamb = scan.segments[2];
  const Eigen::Vector2d middle = 0.5 * (jamb.from_m + jamb.to_m);
  const Eigen::Rotation2Dd tilt(8.0 * M_PI / 180.0);
  jamb.from_m = middle + tilt * (jamb.from_m - middle);
  jamb.to_m = middle + tilt * (jamb.to_m - middle);
  const ScanAlignmentOptions options;
  // The guess: standing still, 10 cm either way.
  const Eigen::Vector3d guess = Eigen::Vector3d::Zero();
  const ScanAlignment a = AlignScans(corridor, scan, guess, Prior(0.1, 0.05), options);
  EXPECT_EQ(a.line_pairs, 3);
  EXPECT_NEAR(a.increment.x(), truth.x(), 0.005);
  EXPECT_LT(std::sqrt(a.covariance(0, 0)), 0.03);
  // The run's tilt does not turn the robot: the walls hold the heading.
  EXPECT_NEAR(a.increment.z(), truth.z(), 1e-3);
  // Taken as exact, the two fits are not parallel: along the corridor only the guess is left.
  corridor.segments[2].direction_var_rad2 = 0.0;
  jamb.direction_var_rad2 = 0.0;
  const ScanAlignment exact = AlignScans(corridor, scan, guess, Prior(0.1, 0.05), options);
  EXPECT_EQ(exact.line_pairs, 2);
  EXPECT_NEAR(exact.increment.x(), guess.x(), 1e-6);
}

TEST(ScanAlignmentTest, NoFeaturesGiveTheGuessBack) {
  const Eigen::Vector3d guess(0.1, 0.0, 0.02);
  const Eigen::Matrix3d prior = Prior(0.05, 0.05);
  const ScanAlignmentOptions options;
  const ScanAlignment a = AlignScans(AlignmentScan{}, Room(), guess, prior, options);
  EXPECT_TRUE(a.increment.isApprox(guess));
  EXPECT_TRUE(a.covariance.isApprox(options.covariance_scale * prior));
  EXPECT_EQ(a.point_pairs + a.line_pairs, 0);
}

TEST(ScanAlignmentTest, TakesTheStaticLookingFeaturesInTheRobotFrame) {
  const SensorMount mount{0.1, 0.0, M_PI / 2};  // 10 cm ahead, turned to the left
  std::vector<PointMeasurement> points(3);
  points[0].range_bearing = {2.0, 0.0};  // straight ahead of the sensor: 2 m left of the robot
  points[1].range_bearing = {1.0, 0.0};
  points[1].person = true;               // people move: left out
  points[2].range_bearing = {std::nan(""), 0.0};
  std::vector<LineReading> lines(2);
  // A wall 1 m ahead of the sensor, its end beams 2 cm off the fitted line.
  lines[0].rho_m = 1.0;
  lines[0].alpha_rad = 0.0;
  lines[0].first_m = {1.02, -1.0};
  lines[0].last_m = {0.98, 1.0};
  lines[0].alpha_var_rad2 = 1e-4;
  lines[1].rho_m = 1.0;  // 1 cm long: too short
  lines[1].first_m = {1.0, 0.0};
  lines[1].last_m = {1.0, 0.01};
  const AlignmentScan scan = AlignmentScanOf(points, lines, mount);
  ASSERT_EQ(scan.points_m.size(), 1u);
  EXPECT_TRUE(scan.points_m[0].isApprox(Eigen::Vector2d(0.1, 2.0)));
  ASSERT_EQ(scan.segments.size(), 1u);
  EXPECT_TRUE(scan.segments[0].from_m.isApprox(Eigen::Vector2d(1.1, 1.0)));
  EXPECT_TRUE(scan.segments[0].to_m.isApprox(Eigen::Vector2d(-0.9, 1.0)));
  EXPECT_EQ(scan.segments[0].direction_var_rad2, 1e-4);
  EXPECT_EQ(scan.skipped, 2);
  EXPECT_EQ(scan.corners, 0);
}

TEST(ScanAlignmentTest, AHostileScanIsCappedToItsNearestPointsAndLongestLines) {
  std::vector<PointMeasurement> points(kMaxAlignmentPoints + 10);
  for (size_t i = 0; i < points.size(); ++i) {
    points[i].range_bearing = {1.0 + static_cast<double>(points.size() - i), 0.0};
  }
  std::vector<LineReading> lines(kMaxAlignmentSegments + 5);
  for (size_t i = 0; i < lines.size(); ++i) {
    // Parallel walls (no corners), the later ones longer.
    lines[i].rho_m = 1.0 + static_cast<double>(i);
    lines[i].first_m = {1.0 + static_cast<double>(i), 0.0};
    lines[i].last_m = {1.0 + static_cast<double>(i), 0.1 * static_cast<double>(i + 1)};
  }
  const AlignmentScan scan = AlignmentScanOf(points, lines, SensorMount{});
  ASSERT_EQ(scan.points_m.size(), static_cast<size_t>(kMaxAlignmentPoints));
  ASSERT_EQ(scan.segments.size(), static_cast<size_t>(kMaxAlignmentSegments));
  EXPECT_EQ(scan.over_cap, 15);
  EXPECT_NEAR(scan.points_m.front().x(), 2.0, 1e-12);  // the nearest first
  EXPECT_NEAR(scan.segments.front().to_m.y(), 0.1 * static_cast<double>(lines.size()), 1e-12);
  EXPECT_EQ(scan.corners, 0);
}

TEST(ScanAlignmentTest, CornersOfTwoLinesArePoints) {
  // A room corner 3 m ahead (the lines end 5 cm short of it) and a door jamb: a wall along the
  // left and its 15 cm end face; and a lone run, whose end is no corner.
  std::vector<LineReading> lines(5);
  const auto set = [](LineReading* l, double rho, double alpha_deg, Eigen::Vector2d first,
                      Eigen::Vector2d last) {
    l->rho_m = rho;
    l->alpha_rad = alpha_deg * M_PI / 180.0;
    l->first_m = first;
    l->last_m = last;
  };
  set(&lines[0], 3.0, 0.0, {3.0, -2.0}, {3.0, -0.05});   // the wall ahead
  set(&lines[1], 0.0, 90.0, {0.5, 0.0}, {2.95, 0.0});    // along the robot's x axis
  set(&lines[2], 1.0, 90.0, {-2.0, 1.0}, {-0.5, 1.0});   // the left wall up to the jamb
  set(&lines[3], 0.5, 180.0, {-0.5, 1.0}, {-0.5, 1.15});  // the jamb's face
  set(&lines[4], 2.0, -90.0, {-3.0, -2.0}, {-1.0, -2.0});  // a lone run
  const AlignmentScan scan = AlignmentScanOf({}, lines, SensorMount{});
  ASSERT_EQ(scan.corners, 2);
  ASSERT_EQ(scan.points_m.size(), 2u);
  EXPECT_TRUE(scan.points_m[0].isApprox(Eigen::Vector2d(3.0, 0.0), 1e-12));
  EXPECT_TRUE(scan.points_m[1].isApprox(Eigen::Vector2d(-0.5, 1.0), 1e-12));
}

TEST(ScanToScanMotionTest, GuessesWithTheVelocityOfTheLastScans) {
  ScanAlignmentOptions options;
  options.velocity_walk_mps2 = 0.0;  // the fixed prior (the filtered one: the next test)
  ScanToScanMotion motion;
  EXPECT_FALSE(motion.MotionTo(Room(), 0.1, options).has_value());
  motion.Keep(AlignmentScan{}, Eigen::Vector3d(1.0, 1.0, M_PI / 2), 1000000);
  motion.Keep(AlignmentScan{}, Eigen::Vector3d(1.0, 1.2, M_PI / 2 + 0.1), 1100000);
  // 2 m/s forward and 1 rad/s; with no feature to align, 0.05 s later the guess stands.
  const std::optional<ScanAlignment> a = motion.MotionTo(Room(), 0.05, options);
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->increment.isApprox(Eigen::Vector3d(0.1, 0.0, 0.05), 1e-9));
  const double sigma = options.guess_speed_sigma_mps * 0.05;
  EXPECT_NEAR(a->covariance(0, 0), options.covariance_scale * sigma * sigma, 1e-12);
  // With the scan's alignment, the velocity is the motion it measured, not the change of the
  // pose the estimator ended the scan with (here 1 m ahead: a correction of the map).
  ScanAlignment measured;
  measured.increment = Eigen::Vector3d(0.04, -0.01, 0.02);
  motion.Keep(AlignmentScan{}, Eigen::Vector3d(1.0, 2.2, M_PI / 2 + 0.1), 1200000, &measured);
  const std::optional<ScanAlignment> b = motion.MotionTo(Room(), 0.05, options);
  ASSERT_TRUE(b);
  EXPECT_TRUE(b->increment.isApprox(Eigen::Vector3d(0.02, -0.005, 0.01), 1e-9));
  motion.Clear();
  EXPECT_FALSE(motion.MotionTo(Room(), 0.1, options).has_value());
}

TEST(ScanToScanMotionTest, CarriesTheVelocitysCovarianceFromScanToScan) {
  const ScanAlignmentOptions options;  // the velocity filtered (the default)
  ASSERT_GT(options.velocity_walk_mps2, 0.0);
  const double dt = 0.1;
  const double walk = options.velocity_walk_mps2 * options.velocity_walk_mps2 * dt;
  const double turn_walk =
      options.velocity_turn_walk_radps * options.velocity_turn_walk_radps * dt;
  ScanToScanMotion motion;
  motion.Keep(AlignmentScan{}, Eigen::Vector3d::Zero(), 1000000);
  // Before any alignment the velocity is not known: the guess's sigmas, grown by the walk.
  const std::optional<ScanAlignment> first = motion.MotionTo(Room(), dt, options);
  ASSERT_TRUE(first);
  const double unknown = options.guess_speed_sigma_mps * options.guess_speed_sigma_mps;
  EXPECT_NEAR(first->covariance(0, 0), dt * dt * (unknown + walk), 1e-12);
  // An alignment that measured the motion across (y) well and along (x) badly: the next guess
  // keeps that, each grown by the walk, not the same fixed sigma for both.
  ScanAlignment measured;
  measured.increment = Eigen::Vector3d(0.03, 0.0, 0.0);
  measured.covariance = Eigen::Vector3d(4e-4, 1e-6, 1e-6).asDiagonal();
  motion.Keep(AlignmentScan{}, Eigen::Vector3d(0.03, 0.0, 0.0), 1100000, &measured);
  const std::optional<ScanAlignment> next = motion.MotionTo(Room(), dt, options);
  ASSERT_TRUE(next);
  EXPECT_TRUE(next->increment.isApprox(measured.increment, 1e-9));
  EXPECT_NEAR(next->covariance(0, 0), 4e-4 + dt * dt * walk, 1e-12);
  EXPECT_NEAR(next->covariance(1, 1), 1e-6 + dt * dt * walk, 1e-12);
  EXPECT_NEAR(next->covariance(2, 2), 1e-6 + dt * dt * turn_walk, 1e-12);
  EXPECT_GT(next->covariance(0, 0), 4.0 * next->covariance(1, 1));
}

TEST(PoseIncrementPredictionTest, ComposesThePoseWithNumericallyCheckedJacobians) {
  const Eigen::Vector3d start(1.0, -2.0, 2.9);
  const Eigen::Vector3d increment(0.3, -0.1, 0.4);
  const Eigen::Matrix3d covariance = Eigen::Vector3d(1e-4, 4e-4, 9e-4).asDiagonal();
  const auto compose = [](const Eigen::Vector3d& pose, const Eigen::Vector3d& inc) {
    RobotMotionAccumulator m(pose);
    m.AddPoseIncrement(inc, Eigen::Matrix3d::Zero());
    return m.pose();
  };
  RobotMotionAccumulator motion(start);
  motion.AddPoseIncrement(increment, covariance);
  EXPECT_NEAR(motion.pose().z(), WrapAngle(2.9 + 0.4), 1e-12);
  const Eigen::MatrixXd f = testing::NumericalJacobian(
      [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return compose(x, increment); }, start,
      {2});
  const Eigen::MatrixXd g = testing::NumericalJacobian(
      [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return compose(start, x); }, increment,
      {2});
  const Eigen::Matrix3d jacobian = motion.jacobian().topLeftCorner<3, 3>();
  const Eigen::Matrix3d noise = motion.noise().topLeftCorner<3, 3>();
  const Eigen::Matrix3d expected_noise = g * covariance * g.transpose();
  EXPECT_TRUE(jacobian.isApprox(f, 1e-6));
  EXPECT_TRUE(noise.isApprox(expected_noise, 1e-6));
  // The heading drift corrects wheel odometry only: untouched by this step.
  EXPECT_EQ(motion.jacobian()(3, 3), 1.0);
  EXPECT_EQ(motion.noise()(3, 3), 0.0);
}

}  // namespace
}  // namespace slammtt
