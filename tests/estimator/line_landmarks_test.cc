// Step 1b, line landmarks (estimator/line_landmarks.h): new landmarks, association by NIS and
// extent, the pose corrected by walls, the budget, bad input.
#include "estimator/line_landmarks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "common/angle.h"
#include "estimator/line_model.h"
#include "estimator/slam_state.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;

// A wall of the map frame: its line and the stretch of it (coordinates along it) in view.
struct Wall {
  Eigen::Vector2d line;
  double from_m;
  double to_m;
};

// Three walls of a room around the origin: x = 3, y = 2, y = -2 (rho = -2 at alpha = pi / 2).
std::vector<Wall> Room() {
  return {{{3.0, 0.0}, -2.0, 2.0}, {{2.0, M_PI / 2}, -3.0, 3.0}, {{-2.0, M_PI / 2}, -3.0, 3.0}};
}

Eigen::Vector2d MapPointToSensor(const Eigen::Vector3d& robot, const SensorMount& mount,
                                 const Eigen::Vector2d& point) {
  const Eigen::Vector2d d = point - SensorPosition(robot, mount);
  const double c = std::cos(robot(2));
  const double s = std::sin(robot(2));
  return Eigen::Vector2d(c * d(0) + s * d(1), -s * d(0) + c * d(1));
}

// The line feature of `wall` seen exactly from `robot`, with sigmas 1 cm and 0.2 degrees.
LineReading See(const Wall& wall, const Eigen::Vector3d& robot, const SensorMount& mount = {}) {
  const Eigen::Vector2d z = PredictLineObservation(robot, wall.line, mount);
  LineReading r;
  r.rho_m = z(0);
  r.alpha_rad = z(1);
  r.rho_var_m2 = 1e-4;
  r.alpha_var_rad2 = std::pow(0.2 * M_PI / 180.0, 2);
  r.first_m = MapPointToSensor(robot, mount, PointOnLine(wall.line, wall.from_m));
  r.last_m = MapPointToSensor(robot, mount, PointOnLine(wall.line, wall.to_m));
  return r;
}

std::vector<LineReading> SeeAll(const std::vector<Wall>& walls, const Eigen::Vector3d& robot) {
  std::vector<LineReading> readings;
  for (const Wall& w : walls) readings.push_back(See(w, robot));
  return readings;
}

class LineLandmarksTest : public ::testing::Test {
 protected:
  SlamState state_{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal()};
  LineLandmarkOptions options_;
  LineGates gates_;
  SensorMount mount_;
  int64_t next_id_ = 1;
  std::vector<LineCandidate> candidates_;

  void SetUp() override { options_.confirm_scans = 1; }  // a feature starts a landmark at once

  LineStepCounts Run(const std::vector<LineReading>& lines, int64_t utime) {
    return UpdateLineLandmarks(lines, utime, options_, gates_, mount_, &next_id_, &state_,
                               &candidates_);
  }
};

TEST_F(LineLandmarksTest, FirstSightingsBecomeLandmarksAndLaterOnesAssociate) {
  const std::vector<Wall> room = Room();
  LineStepCounts counts = Run(SeeAll(room, state_.robot_pose()), kSecond);
  EXPECT_EQ(counts.features, 3);
  EXPECT_EQ(counts.new_landmarks, 3);
  ASSERT_EQ(state_.num_lines(), 3);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d line = state_.line_params(k);
    const Eigen::Vector2d n(std::cos(line(1)), std::sin(line(1)));
    // Two points of the true wall lie on the landmark's line.
    for (double t : {room[static_cast<size_t>(k)].from_m, room[static_cast<size_t>(k)].to_m}) {
      EXPECT_NEAR(PointOnLine(room[static_cast<size_t>(k)].line, t).dot(n), line(0), 1e-9);
    }
    const LineRecord& record = state_.line(k).record;
    EXPECT_EQ(record.id, k + 1);
    EXPECT_NEAR(record.extent_to_m - record.extent_from_m,
                room[static_cast<size_t>(k)].to_m - room[static_cast<size_t>(k)].from_m, 1e-9);
  }
  EXPECT_EQ(next_id_, 4);
  std::vector<double> first_rho_var;
  for (int k = 0; k < 3; ++k) first_rho_var.push_back(state_.LineCovariance(k)(0, 0));

  counts = Run(SeeAll(room, state_.robot_pose()), 2 * kSecond);
  EXPECT_EQ(counts.new_landmarks, 0);
  EXPECT_EQ(counts.associated, 3);
  EXPECT_EQ(counts.level1_updates, 3);  // each wall compatible with its own landmark only
  EXPECT_EQ(state_.num_lines(), 3);
  for (const StateLine& l : state_.lines()) {
    EXPECT_EQ(l.record.hits, 2);
    EXPECT_EQ(l.record.last_seen_utime, 2 * kSecond);
  }
  // Seen again with the same (floored) noise, each landmark's rho variance about halves.
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(state_.LineCovariance(k)(0, 0), 0.55 * first_rho_var[static_cast<size_t>(k)]);
  }
}

TEST_F(LineLandmarksTest, WallsCorrectAWrongPose) {
  // The walls known to 1 mm and 0.05 degrees; the robot believes it is 0.15 m and 3 degrees
  // away from where it is, with a covariance that allows it.
  const std::vector<Wall> room = Room();
  for (const Wall& w : room) {
    state_.AddLine(w.line, Eigen::Matrix<double, 2, 3>::Zero(),
                   Eigen::Vector2d(1e-6, std::pow(0.05 * M_PI / 180.0, 2)).asDiagonal(),
                   LineRecord{next_id_++, 1, 0, 0, 0, w.from_m, w.to_m});
  }
  const Eigen::Vector3d truth(0.4, -0.3, 0.2);
  auto mean = state_.mean();
  mean.head<3>() = truth + Eigen::Vector3d(0.15, -0.1, 3.0 * M_PI / 180.0);
  auto cov = state_.covariance();
  cov.topLeftCorner<3, 3>() = Eigen::Vector3d(0.04, 0.04, std::pow(5.0 * M_PI / 180, 2))
                                  .asDiagonal();
  const LineStepCounts counts = Run(SeeAll(room, truth), kSecond);
  EXPECT_EQ(counts.new_landmarks, 0);
  EXPECT_EQ(counts.associated, 3);
  const Eigen::Vector3d pose = state_.robot_pose();
  EXPECT_LT((pose.head<2>() - truth.head<2>()).norm(), 0.01);
  EXPECT_LT(std::abs(WrapAngle(pose(2) - truth(2))), 0.2 * M_PI / 180.0);
}

TEST_F(LineLandmarksTest, ACollinearWallBeyondTheGapIsANewLandmark) {
  const Wall near{{3.0, 0.0}, -1.0, 1.0};
  Run({See(near, state_.robot_pose())}, kSecond);
  ASSERT_EQ(state_.num_lines(), 1);
  // The same line 2.5 m further along it: beyond extent_gap_m (1 m) of the seen extent.
  const Wall far{{3.0, 0.0}, 3.5, 5.0};
  LineStepCounts counts = Run({See(far, state_.robot_pose())}, 2 * kSecond);
  EXPECT_EQ(counts.associated, 0);
  EXPECT_EQ(counts.new_landmarks, 1);
  EXPECT_EQ(state_.num_lines(), 2);
  // A piece that starts 0.5 m after the first one's end (a door) joins it and extends it.
  const Wall door{{3.0, 0.0}, 1.5, 2.5};
  counts = Run({See(door, state_.robot_pose())}, 3 * kSecond);
  EXPECT_EQ(counts.new_landmarks, 0);
  EXPECT_EQ(counts.associated, 1);
  EXPECT_NEAR(state_.line(0).record.extent_to_m, 2.5, 1e-6);
}

TEST_F(LineLandmarksTest, TheBudgetLimitsUpdatesNotAssociations) {
  const std::vector<Wall> room = Room();
  Run(SeeAll(room, state_.robot_pose()), kSecond);
  options_.max_updates_per_scan = 1;
  const uint64_t revision = state_.revision();
  const LineStepCounts counts = Run(SeeAll(room, state_.robot_pose()), 2 * kSecond);
  EXPECT_EQ(counts.associated, 3);
  EXPECT_EQ(counts.level1_updates + counts.level2_updates, 1);
  EXPECT_EQ(counts.updates_skipped, 2);
  EXPECT_NE(state_.revision(), revision);
  int updated_now = 0;
  for (const StateLine& l : state_.lines()) {
    EXPECT_EQ(l.record.hits, 2);
    updated_now += l.record.last_update_utime == 2 * kSecond ? 1 : 0;
  }
  EXPECT_EQ(updated_now, 1);
}

TEST_F(LineLandmarksTest, BadFeaturesAreRejectedAndCounted) {
  std::vector<LineReading> bad(5, See(Room()[0], state_.robot_pose()));
  bad[0].rho_m = std::numeric_limits<double>::quiet_NaN();
  bad[1].rho_m = -1.0;
  bad[2].alpha_rad = 4.0;
  bad[3].rho_alpha_cov_m_rad = 1.0;  // |cov| above sqrt(var var)
  bad[4].last_m(0) = std::numeric_limits<double>::infinity();
  const LineStepCounts counts = Run(bad, kSecond);
  EXPECT_EQ(counts.rejected, 5);
  EXPECT_EQ(counts.first_rejection, "a line feature has a non-finite value");
  EXPECT_EQ(state_.num_lines(), 0);
  EXPECT_EQ(state_.dim(), SlamState::kRobotDim);
}

TEST_F(LineLandmarksTest, DisabledOrCappedAddsNothing) {
  options_.enabled = false;
  EXPECT_EQ(Run(SeeAll(Room(), state_.robot_pose()), kSecond).new_landmarks, 0);
  EXPECT_EQ(state_.num_lines(), 0);
  options_.enabled = true;
  options_.max_landmarks = 2;
  const LineStepCounts counts = Run(SeeAll(Room(), state_.robot_pose()), 2 * kSecond);
  EXPECT_EQ(counts.new_landmarks, 2);
  EXPECT_EQ(counts.refused, 1);
  EXPECT_EQ(state_.num_lines(), 2);
}

TEST_F(LineLandmarksTest, ALineBecomesALandmarkOnlyWhenItStays) {
  options_.confirm_scans = 3;
  const Wall wall{{3.0, 0.0}, -1.0, 1.0};
  const int64_t step = kSecond / 10;
  EXPECT_EQ(Run({See(wall, state_.robot_pose())}, step).candidates, 1);
  EXPECT_EQ(Run({See(wall, state_.robot_pose())}, 2 * step).new_landmarks, 0);
  EXPECT_EQ(state_.dim(), SlamState::kRobotDim);  // candidates stay outside the state
  LineStepCounts counts = Run({See(wall, state_.robot_pose())}, 3 * step);
  EXPECT_EQ(counts.new_landmarks, 1);
  EXPECT_EQ(counts.candidates, 0);
  ASSERT_EQ(state_.num_lines(), 1);
  // A straight run that moves 0.2 m per scan (people walking side by side) never stays.
  for (int k = 0; k < 10; ++k) {
    const Wall walking{{-1.0 - 0.2 * k, M_PI / 2}, -0.5, 0.5};
    counts = Run({See(walking, state_.robot_pose())}, (4 + k) * step);
    EXPECT_EQ(counts.new_landmarks, 0);
  }
  EXPECT_EQ(state_.num_lines(), 1);
  // A candidate unseen for longer than the timeout is dropped.
  const Wall other{{-2.0, 0.0}, -1.0, 1.0};
  Run({See(other, state_.robot_pose())}, 20 * step);
  Run({See(other, state_.robot_pose())}, 21 * step);
  counts = Run({}, 30 * step);
  EXPECT_EQ(counts.candidates, 0);
  EXPECT_EQ(Run({See(other, state_.robot_pose())}, 31 * step).new_landmarks, 0);
}

TEST_F(LineLandmarksTest, PointFeaturesOnALineLandmarkArePiecesOfIt) {
  Run({See({{3.0, 0.0}, -1.0, 1.0}, state_.robot_pose())}, kSecond);
  ASSERT_EQ(state_.num_lines(), 1);
  auto at = [](double x, double y) {
    return Eigen::Vector2d(std::hypot(x, y), std::atan2(y, x));
  };
  // On the wall; 0.08 m in front of it; at its seen end plus 0.15 m (a door jamb); 0.3 m in
  // front (a person); beyond the end margin; on the far side of the room.
  const std::vector<Eigen::Vector2d> points = {at(3.0, 0.5), at(2.92, -0.2), at(3.0, 1.15),
                                               at(2.7, 0.0), at(3.0, 1.5), at(-3.0, 0.0)};
  EXPECT_EQ(PointsOnLineLandmarks(points, options_, mount_, state_),
            (std::vector<uint8_t>{1, 1, 1, 0, 0, 0}));
  options_.point_on_line_m = 0.0;
  options_.point_behind_line_m = 0.0;
  EXPECT_EQ(PointsOnLineLandmarks(points, options_, mount_, state_),
            std::vector<uint8_t>(points.size(), 0));
}

TEST_F(LineLandmarksTest, PointFeaturesJustBehindALineLandmarkArePiecesOfItToo) {
  // A wall 3 m ahead with dropouts: its short runs are point features whose fitted centres lie
  // behind it, where the laser cannot see.
  Run({See({{3.0, 0.0}, -1.0, 1.0}, state_.robot_pose())}, kSecond);
  ASSERT_EQ(state_.num_lines(), 1);
  auto at = [](double x, double y) {
    return Eigen::Vector2d(std::hypot(x, y), std::atan2(y, x));
  };
  // 0.4 m behind it; 0.7 m behind (beyond point_behind_line_m); 0.4 m behind but beyond the
  // end margin; 0.4 m in front of it (a person).
  const std::vector<Eigen::Vector2d> points = {at(3.4, 0.0), at(3.7, 0.3), at(3.4, 1.5),
                                               at(2.6, 0.0)};
  ASSERT_EQ(options_.point_behind_line_m, 0.6);
  EXPECT_EQ(PointsOnLineLandmarks(points, options_, mount_, state_),
            (std::vector<uint8_t>{1, 0, 0, 0}));
  options_.point_behind_line_m = 0.0;
  EXPECT_EQ(PointsOnLineLandmarks(points, options_, mount_, state_),
            std::vector<uint8_t>(points.size(), 0));
}

TEST(SlamStateLinesTest, LineSlotsFollowTheRemovalOfObjects) {
  SlamState state(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.01);
  ObjectRecord record;
  const int point = state.AddObject({1.0, 2.0}, Eigen::Matrix<double, 2, 3>::Zero(),
                                    Eigen::Matrix2d::Identity() * 0.1, record);
  LineRecord line_record;
  line_record.id = 7;
  Eigen::Matrix<double, 2, 3> g = Eigen::Matrix<double, 2, 3>::Zero();
  g(1, 2) = 1.0;  // the line's alpha error is the heading's
  state.AddLine({3.0, 0.5}, g, Eigen::Matrix2d::Identity() * 1e-4, line_record);
  EXPECT_NEAR(state.covariance()(state.line(0).param_index + 1, 2), 0.01, 1e-15);
  state.RemoveObjects({point});
  ASSERT_EQ(state.num_lines(), 1);
  EXPECT_EQ(state.line(0).param_index, SlamState::kRobotDim);
  EXPECT_EQ(state.dim(), SlamState::kRobotDim + 2);
  EXPECT_EQ(state.line_params(0), Eigen::Vector2d(3.0, 0.5));
  EXPECT_NEAR(state.LineCovariance(0)(1, 1), 0.01 + 1e-4, 1e-15);
  EXPECT_EQ(state.line(0).record.id, 7);
}

}  // namespace
}  // namespace slammtt
