// The estimator's per-scan input to the smoother (estimator/static_observations.h,
// estimator/smoother_input.h): which associations are static observations, the odometry
// increment in the previous robot frame, removals reported once.
#include <gtest/gtest.h>

#include <cmath>

#include "estimator/smoother_input.h"
#include "estimator/static_observations.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

TEST(StaticObservationsTest, LandmarksAndTentativeLandmarksOfKindOtherWithPointMeasurements) {
  StepScene scene;
  const int landmark = scene.AddLandmark({5, 0}, 0.1, 11);
  const int mover = scene.AddMover({0, 5}, 0.1, {1, 0}, 0.1, ObjectClass::kMoving, 12);
  const int tentative = scene.AddLandmark({5, 5}, 0.1, 13);
  scene.state.object(tentative).record.confirmed = false;
  const int person = scene.AddLandmark({-5, 5}, 0.1, 14);
  scene.state.object(person).record.kind = ObjectKind::kPerson;
  const int second = scene.AddLandmark({8, -2}, 0.1, 15);
  const int undecided = scene.AddMover({-3, -3}, 0.1, {0, 0}, 0.1, ObjectClass::kUndecided, 16);
  const int z_landmark = scene.Measure({5, 0});
  const int z_mover = scene.Measure({0, 5});
  const int z_tentative = scene.Measure({5, 5});
  const int z_person = scene.Measure({-5, 5});
  const int z_free = scene.Measure({20, 0});
  const int z_person_feature = scene.Measure({8, -2});
  scene.measurements[static_cast<size_t>(z_person_feature)].person = true;
  const int z_undecided = scene.Measure({-3, -3});
  Assignment assignment(static_cast<int>(scene.measurements.size()), scene.state.num_objects());
  assignment.Set(z_landmark, landmark);
  assignment.Set(z_mover, mover);
  assignment.Set(z_tentative, tentative);
  assignment.Set(z_person, person);
  assignment.Set(z_person_feature, second);
  assignment.Set(z_undecided, undecided);
  (void)z_free;

  const std::vector<StaticObservation> observations =
      StaticObservations(scene.measurements, assignment, scene.state);
  ASSERT_EQ(observations.size(), 3u);
  EXPECT_EQ(observations[0].landmark_id, 11);
  EXPECT_FALSE(observations[0].tentative);
  // Not yet confirmed, not yet classified: held by the smoother until they are landmarks.
  EXPECT_EQ(observations[1].landmark_id, 13);
  EXPECT_TRUE(observations[1].tentative);
  EXPECT_EQ(observations[2].landmark_id, 16);
  EXPECT_TRUE(observations[2].tentative);
  EXPECT_EQ(observations[0].range_bearing,
            scene.measurements[static_cast<size_t>(z_landmark)].range_bearing);
  EXPECT_EQ(observations[0].covariance,
            scene.measurements[static_cast<size_t>(z_landmark)].covariance);
}

TEST(MotionIncrementTest, IsTheEndPoseInTheStartFrameWithTheNoiseRotatedIntoIt) {
  RobotMotion motion;
  motion.continues = true;
  motion.from_pose = Eigen::Vector3d(1.0, 2.0, M_PI / 2);
  // 0.5 m forward (map +y), 0.1 m left (map -x), turned 0.2 rad.
  motion.to_pose = Eigen::Vector3d(0.9, 2.5, M_PI / 2 + 0.2);
  motion.noise = Eigen::Vector3d(4.0, 1.0, 0.5).asDiagonal();
  motion.noise(0, 2) = motion.noise(2, 0) = 0.3;  // map x with heading
  Eigen::Vector3d increment;
  Eigen::Matrix3d covariance;
  MotionIncrement(motion, &increment, &covariance);
  EXPECT_NEAR(increment(0), 0.5, 1e-12);
  EXPECT_NEAR(increment(1), 0.1, 1e-12);
  EXPECT_NEAR(increment(2), 0.2, 1e-12);
  // Map x is the start frame's -y, map y its x.
  EXPECT_NEAR(covariance(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(covariance(1, 1), 4.0, 1e-12);
  EXPECT_NEAR(covariance(2, 2), 0.5, 1e-12);
  EXPECT_NEAR(covariance(1, 2), -0.3, 1e-12);
  EXPECT_NEAR(covariance(0, 2), 0.0, 1e-12);
  EXPECT_EQ(covariance, covariance.transpose());
}

TEST(MotionIncrementTest, WrapsTheHeadingChangeAcrossPi) {
  RobotMotion motion;
  motion.from_pose = Eigen::Vector3d(0, 0, 3.1);
  motion.to_pose = Eigen::Vector3d(0, 0, -3.1);
  Eigen::Vector3d increment;
  Eigen::Matrix3d covariance;
  MotionIncrement(motion, &increment, &covariance);
  EXPECT_NEAR(increment(2), 2 * M_PI - 6.2, 1e-12);
}

ObjectEstimate Landmark(int64_t id, ObjectClass object_class = ObjectClass::kStatic) {
  ObjectEstimate e;
  e.id = id;
  e.object_class = object_class;
  e.confirmed = true;
  return e;
}

ScanResult Result(int64_t utime, bool continues, std::vector<ObjectEstimate> objects,
                  std::vector<int64_t> observed) {
  ScanResult result;
  result.processed = true;
  result.utime = utime;
  result.motion.continues = continues;
  result.motion.from_pose = Eigen::Vector3d(0, 0, 0);
  result.motion.to_pose = Eigen::Vector3d(continues ? 0.1 : 0.0, 0, 0);
  result.objects = std::move(objects);
  for (const int64_t id : observed) {
    result.static_observations.push_back(
        StaticObservation{id, Eigen::Vector2d(3, 0.1), Eigen::Matrix2d::Identity()});
  }
  return result;
}

TEST(SmootherInputBuilderTest, ReportsALandmarkThatLeftTheStaticMapOnce) {
  SmootherInputBuilder builder;
  SensorMount mount;
  mount.forward_m = 0.1;
  const SmootherScanInput first =
      builder.Build(Result(1, false, {Landmark(1), Landmark(2)}, {1, 2}), mount);
  EXPECT_FALSE(first.continues);
  EXPECT_EQ(first.increment, Eigen::Vector3d::Zero());
  EXPECT_EQ(first.mount.forward_m, 0.1);
  EXPECT_EQ(first.observations.size(), 2u);
  EXPECT_TRUE(first.removed_landmark_ids.empty());

  // Landmark 2 turned moving, landmark 3 (never observed) vanished.
  const SmootherScanInput second = builder.Build(
      Result(2, true, {Landmark(1), Landmark(2, ObjectClass::kMoving)}, {1}), mount);
  EXPECT_TRUE(second.continues);
  EXPECT_NEAR(second.increment(0), 0.1, 1e-12);
  EXPECT_EQ(second.removed_landmark_ids, std::vector<int64_t>{2});

  // Gone for good: not reported again; 1 pruned now.
  const SmootherScanInput third = builder.Build(Result(3, true, {}, {}), mount);
  EXPECT_EQ(third.removed_landmark_ids, std::vector<int64_t>{1});
  const SmootherScanInput fourth = builder.Build(Result(4, true, {}, {}), mount);
  EXPECT_TRUE(fourth.removed_landmark_ids.empty());
}

TEST(SmootherInputBuilderTest, AnUndecidedObjectIsNotRemoved) {
  SmootherInputBuilder builder;
  builder.Build(Result(1, false, {Landmark(1)}, {1}), SensorMount{});
  const SmootherScanInput next = builder.Build(
      Result(2, true, {Landmark(1, ObjectClass::kUndecided)}, {}), SensorMount{});
  EXPECT_TRUE(next.removed_landmark_ids.empty());
  ObjectEstimate person = Landmark(1);
  person.kind = ObjectKind::kPerson;
  EXPECT_EQ(builder.Build(Result(3, true, {person}, {}), SensorMount{}).removed_landmark_ids,
            std::vector<int64_t>{1});
}

TEST(SmootherInputBuilderTest, ANewTimeBaseForgetsWhatWasReported) {
  SmootherInputBuilder builder;
  builder.Build(Result(1, false, {Landmark(1)}, {1}), SensorMount{});
  // The estimator started over: its map is empty, and nothing of the old one is "removed".
  const SmootherScanInput restart = builder.Build(Result(2, false, {}, {}), SensorMount{});
  EXPECT_FALSE(restart.continues);
  EXPECT_TRUE(restart.removed_landmark_ids.empty());
}

TEST(SmootherInputBuilderTest, AnObservedLandmarkIsNeverRemovedInTheSameScan) {
  SmootherInputBuilder builder;
  builder.Build(Result(1, false, {Landmark(1)}, {1}), SensorMount{});
  // Observed while its reported estimate is not a confirmed static one.
  ObjectEstimate unreported = Landmark(1);
  unreported.confirmed = false;
  const SmootherScanInput next = builder.Build(Result(2, true, {unreported}, {1}), SensorMount{});
  EXPECT_TRUE(next.removed_landmark_ids.empty());
}

}  // namespace
}  // namespace slammtt
