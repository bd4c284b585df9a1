// The smoother's estimate fed back into the filter (estimator/smoother_feedback.h): which
// states move, that the covariance does not, the pose carried forward from an earlier scan.
#include <gtest/gtest.h>

#include <cmath>

#include "estimator/smoother_feedback.h"
#include "geometry/pose2.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

TEST(SmootherFeedbackTest, MovesThePoseAndTheConfirmedStaticLandmarksOnly) {
  StepScene scene;
  const int landmark = scene.AddLandmark({5, 0}, 0.1, 11);
  const int mover = scene.AddMover({0, 5}, 0.1, {1, 0}, 0.1, ObjectClass::kMoving, 12);
  const int tentative = scene.AddLandmark({5, 5}, 0.1, 13);
  scene.state.object(tentative).record.confirmed = false;
  const int person = scene.AddLandmark({-5, 5}, 0.1, 14);
  scene.state.object(person).record.kind = ObjectKind::kPerson;
  const int untouched = scene.AddLandmark({8, -2}, 0.1, 15);
  // An archived landmark (the local window's), stored from the state and then taken out.
  const int leaving = scene.AddLandmark({30, 0}, 0.2, 16);
  LandmarkArchive archive;
  ASSERT_EQ(archive.Store(scene.state, {leaving}), 1);
  scene.state.RemoveObjects({leaving});
  const Eigen::MatrixXd covariance_before = scene.state.covariance();
  const Eigen::Vector2d mover_before = scene.state.position(mover);
  const Eigen::Vector2d tentative_before = scene.state.position(tentative);
  const Eigen::Vector2d person_before = scene.state.position(person);
  const Eigen::Vector2d untouched_before = scene.state.position(untouched);

  SmoothedEstimate smoothed;
  smoothed.utime = 100;
  smoothed.landmarks = {{11, {5.2, -0.1}}, {12, {1, 1}}, {13, {2, 2}}, {14, {3, 3}},
                        {16, {30.5, 0.5}}, {99, {4, 4}}};
  const Eigen::Vector3d pose_now(0.3, -0.4, 3.1 + 0.1);  // the heading is wrapped
  const FeedbackCounts counts = ShiftToSmoothedEstimate(smoothed, pose_now, &scene.state, &archive);

  EXPECT_TRUE(counts.applied);
  EXPECT_EQ(counts.landmarks_moved, 1);
  EXPECT_EQ(counts.archived_moved, 1);
  EXPECT_EQ(counts.landmarks_unknown, 4);  // the mover, the tentative one, the person, id 99
  EXPECT_NEAR(counts.pose_shift_m, 0.5, 1e-12);
  EXPECT_NEAR(counts.heading_shift_rad, 3.2 - 2.0 * M_PI, 1e-12);
  EXPECT_NEAR(counts.largest_landmark_shift_m, std::hypot(0.2, 0.1), 1e-12);
  EXPECT_NEAR(scene.state.robot_pose()(0), 0.3, 1e-12);
  EXPECT_NEAR(scene.state.robot_pose()(1), -0.4, 1e-12);
  EXPECT_NEAR(scene.state.robot_pose()(2), 3.2 - 2.0 * M_PI, 1e-12);
  EXPECT_TRUE(scene.state.position(landmark).isApprox(Eigen::Vector2d(5.2, -0.1)));
  EXPECT_EQ(scene.state.position(mover), mover_before);
  EXPECT_EQ(scene.state.position(tentative), tentative_before);
  EXPECT_EQ(scene.state.position(person), person_before);
  EXPECT_EQ(scene.state.position(untouched), untouched_before);
  EXPECT_TRUE(archive.landmarks().at(16).position_m.isApprox(Eigen::Vector2d(30.5, 0.5)));
  // No information is added: the covariance is exactly the same.
  EXPECT_EQ(Eigen::MatrixXd(scene.state.covariance()), covariance_before);
}

TEST(SmootherFeedbackTest, CarriesAnEarlierScansPoseForwardAlongTheFiltersMotion) {
  const Eigen::Vector3d filter_then(1.0, 2.0, 0.3);
  const Eigen::Vector3d motion(0.8, 0.1, 0.2);
  const Eigen::Vector3d filter_now = ComposePoses(filter_then, motion);
  const Eigen::Vector3d smoothed_then(1.1, 1.9, 0.25);
  // The same scan: the smoother's pose itself.
  EXPECT_TRUE(CarryPoseForward(smoothed_then, filter_then, filter_then).isApprox(smoothed_then));
  // A later one: the filter's motion since, from the smoother's pose.
  const Eigen::Vector3d now = CarryPoseForward(smoothed_then, filter_then, filter_now);
  EXPECT_TRUE(PoseBetween(smoothed_then, now).isApprox(motion, 1e-12));
}

TEST(SmootherFeedbackTest, PoseHistoryFindsRecentScansAndForgetsTheFrameBeforeACorrection) {
  ScanPoseHistory history(3);
  EXPECT_FALSE(history.At(1).has_value());
  for (int k = 1; k <= 4; ++k) history.Record(k, Eigen::Vector3d(k, 0, 0));
  EXPECT_FALSE(history.At(1).has_value());  // beyond the capacity
  ASSERT_TRUE(history.At(2).has_value());
  EXPECT_EQ((*history.At(2))(0), 2.0);
  EXPECT_FALSE(history.At(5).has_value());
  history.KeepNewestAs(Eigen::Vector3d(9, 9, 0));
  EXPECT_FALSE(history.At(3).has_value());
  ASSERT_TRUE(history.At(4).has_value());
  EXPECT_EQ((*history.At(4))(0), 9.0);
}

}  // namespace
}  // namespace slammtt
