// Level 1 (estimator/level1.h) and the nearest-neighbour association of baseline (a)
// (estimator/nearest_neighbour.h).
#include "estimator/level1.h"

#include <gtest/gtest.h>

#include <vector>

#include "estimator/nearest_neighbour.h"
#include "estimator/scan_gating.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

// Landmarks 0 and 1 far apart, each with one measurement; landmarks 2 and 3 side by side with
// one measurement between them (ambiguous).
struct TwoClearOneAmbiguous : StepScene {
  TwoClearOneAmbiguous() {
    AddLandmark({5.0, 0.0}, 0.05);
    AddLandmark({0.0, 5.0}, 0.05);
    AddLandmark({-5.0, 0.1}, 0.05);
    AddLandmark({-5.0, -0.1}, 0.05);
    Measure({5.02, 0.0});
    Measure({0.0, 5.03});
    Measure({-5.0, 0.02});  // a little nearer landmark 2
  }
};

TEST(Level1Test, AppliesThePairsJSettlesAndReturnsTheAmbiguousRest) {
  TwoClearOneAmbiguous scene;
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  ASSERT_EQ(gating.compatible.size(), 4u);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  Assignment assignment(3, 4);
  const std::vector<Candidate> ambiguous =
      AssociateLevel1(gating.compatible, scan, scene.options, &predicted, &scene.state,
                      &assignment, &scene.counts);
  EXPECT_EQ(scene.counts.level1_updates, 2);
  EXPECT_EQ(assignment.ObjectOf(0), 0);
  EXPECT_EQ(assignment.ObjectOf(1), 1);
  EXPECT_TRUE(assignment.MeasurementFree(2));
  ASSERT_EQ(ambiguous.size(), 2u);
  EXPECT_EQ(ambiguous[0].measurement, 2);
  EXPECT_EQ(ambiguous[0].object, 2);
  EXPECT_EQ(ambiguous[1].object, 3);
}

TEST(NearestNeighbourTest, EachMeasurementTakesItsNearestObjectOneToOne) {
  TwoClearOneAmbiguous scene;
  // A fourth measurement right at landmark 3: each of the two measurements between the side by
  // side landmarks takes its nearest.
  scene.Measure({-5.0, -0.1});
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  Assignment assignment(4, 4);
  AssociateNearestNeighbours(gating.compatible, scan, scene.options, &predicted, &scene.state,
                             &assignment, &scene.counts);
  EXPECT_EQ(scene.counts.level1_updates, 4);
  EXPECT_EQ(assignment.ObjectOf(0), 0);
  EXPECT_EQ(assignment.ObjectOf(1), 1);
  EXPECT_EQ(assignment.ObjectOf(3), 3);
  EXPECT_EQ(assignment.ObjectOf(2), 2);
}

TEST(NearestNeighbourTest, TheCloserMeasurementWinsASharedNearestObject) {
  StepScene scene;
  scene.AddLandmark({5.0, 0.0}, 0.05);
  scene.Measure({5.15, 0.0});  // 15 cm off
  scene.Measure({5.02, 0.0});  // 2 cm off: wins
  ObservationPredictions predicted(scene.options.sensor);
  const ScanGating gating = GateScan(scene.measurements, predicted.At(scene.state), scene.options);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  Assignment assignment(2, 1);
  AssociateNearestNeighbours(gating.compatible, scan, scene.options, &predicted, &scene.state,
                             &assignment, &scene.counts);
  EXPECT_EQ(assignment.ObjectOf(1), 0);
  EXPECT_TRUE(assignment.MeasurementFree(0));
  EXPECT_EQ(scene.counts.level1_updates, 1);
}

}  // namespace
}  // namespace slammtt
