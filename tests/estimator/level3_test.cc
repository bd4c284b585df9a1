// Level 3 (estimator/level3.h) and the manoeuvres before it (estimator/manoeuvres.h).
#include "estimator/level3.h"

#include <gtest/gtest.h>

#include <vector>

#include "estimator/manoeuvres.h"
#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

TEST(Level3Test, TakesAFreePairBetweenD1AndD2) {
  StepScene scene;
  const int landmark = scene.AddLandmark({5.0, 0.0}, 0.05);
  const int z = scene.Measure({5.18, 0.0});
  const double nis = scene.Nis(z, landmark);
  ASSERT_GT(nis, scene.options.gate_d1_chi2);
  ASSERT_LT(nis, scene.options.gate_d2_chi2);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  Assignment assignment(1, 1);
  const std::vector<Candidate> candidates =
      Level3Candidates(scan, scene.options, &predicted, scene.state, assignment);
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_EQ(candidates[0].nis, nis);
  EXPECT_EQ(candidates[0].cost, PairCost(scene.measurements[0], scene.Predictions()[0], nis));
  AssociateLevel3(scan, scene.options, &predicted, &scene.state, &assignment, &scene.counts);
  EXPECT_EQ(scene.counts.level3_updates, 1);
  EXPECT_EQ(assignment.ObjectOf(z), landmark);
  // Taken pairs are not candidates.
  EXPECT_TRUE(Level3Candidates(scan, scene.options, &predicted, scene.state, assignment).empty());
}

TEST(Level3Test, AWideObjectDoesNotTakeAWellKnownLandmarksMeasurementByItsSmallerNis) {
  // A landmark known to 1 cm and an object known to 1 m just behind it; the measurement is
  // 5 cm behind the landmark: NIS 2.3 to the landmark, 0.02 to the wide object, but the cost
  // (NIS + ln det S) prefers the landmark.
  StepScene scene;
  const int landmark = scene.AddLandmark({3.0, 0.0}, 0.01);
  const int wide = scene.AddMover({3.2, 0.0}, 1.0, {0.0, 0.0}, 0.5);
  const int z = scene.Measure({3.05, 0.0});
  ASSERT_GT(scene.Nis(z, landmark), 10.0 * scene.Nis(z, wide));
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  Assignment assignment(1, 2);
  AssociateLevel3(scan, scene.options, &predicted, &scene.state, &assignment, &scene.counts);
  EXPECT_EQ(assignment.ObjectOf(z), landmark);
  EXPECT_TRUE(assignment.ObjectFree(wide));
}

// A MOVING object whose measurement lies outside its gates d2 and dn by the steady walk (its
// position known to 5 cm) but inside gate d2 of a velocity jump over the last 0.125 s.
struct StoppedWalker : StepScene {
  int walker = -1;
  StoppedWalker() {
    walker = AddMover({4.0, 0.0}, 0.05, {1.0, 0.0}, 0.05);
    Measure({3.7, 0.0});
  }
};

TEST(ManoeuvreTest, AMoverOutsideItsGateButInsideTheJumpsGetsTheJump) {
  StoppedWalker scene;
  ASSERT_GT(scene.Nis(0, scene.walker), scene.options.new_object_gate_dn_chi2);
  ASSERT_GT(scene.options.new_object_gate_dn_chi2, scene.options.gate_d2_chi2);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  const Assignment assignment(1, 1);
  const int v = scene.state.object(scene.walker).velocity_index;
  const double velocity_var_before = scene.state.covariance()(v, v);
  const double dt = 0.125;
  GiveManoeuvringMoversAVelocityJump(dt, scan, scene.options, &predicted, &scene.state,
                                     assignment, &scene.counts);
  EXPECT_EQ(scene.counts.manoeuvres, 1);
  const double sigma = scene.options.manoeuvre_velocity_sigma_mps;
  EXPECT_DOUBLE_EQ(scene.state.covariance()(v, v), velocity_var_before + sigma * sigma);
  EXPECT_LT(scene.Nis(0, scene.walker), scene.options.gate_d2_chi2);
}

// A free measurement already inside the mover's gate d2 as it is: level 3 can take it without a
// jump, so there is none (the velocity of a walker seen far away, whose measurement missed gate
// d1 by noise, is not thrown away; s1-crossing: docs/targets.md).
TEST(ManoeuvreTest, NoJumpWhenLevel3CanTakeTheMeasurementWithoutIt) {
  StepScene scene;
  const int walker = scene.AddMover({4.0, 0.0}, 0.05, {1.0, 0.0}, 0.05);
  scene.Measure({3.7, 0.0});   // outside d2: the jump would take it...
  scene.Measure({4.19, 0.0});  // ...but this one lies between d1 and d2 already
  ASSERT_GT(scene.Nis(1, walker), scene.options.gate_d1_chi2);
  ASSERT_LT(scene.Nis(1, walker), scene.options.gate_d2_chi2);
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  GiveManoeuvringMoversAVelocityJump(0.125, scan, scene.options, &predicted, &scene.state,
                                     Assignment(2, 1), &scene.counts);
  EXPECT_EQ(scene.counts.manoeuvres, 0);
}

TEST(ManoeuvreTest, NoJumpForUndecidedObjectsTakenObjectsOrWhenOff) {
  {
    StoppedWalker scene;
    scene.state.object(scene.walker).record.object_class = ObjectClass::kUndecided;
    const std::vector<uint8_t> may_update = scene.AllMayUpdate();
    const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
    ObservationPredictions predicted(scene.options.sensor);
    GiveManoeuvringMoversAVelocityJump(0.125, scan, scene.options, &predicted, &scene.state,
                                       Assignment(1, 1), &scene.counts);
    EXPECT_EQ(scene.counts.manoeuvres, 0) << "undecided";
  }
  {
    StoppedWalker scene;
    const std::vector<uint8_t> may_update = scene.AllMayUpdate();
    const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
    ObservationPredictions predicted(scene.options.sensor);
    Assignment measured(1, 1);
    measured.Set(0, 0);
    GiveManoeuvringMoversAVelocityJump(0.125, scan, scene.options, &predicted, &scene.state,
                                       measured, &scene.counts);
    EXPECT_EQ(scene.counts.manoeuvres, 0) << "measured already";
    scene.options.manoeuvre_velocity_sigma_mps = 0.0;
    GiveManoeuvringMoversAVelocityJump(0.125, scan, scene.options, &predicted, &scene.state,
                                       Assignment(1, 1), &scene.counts);
    EXPECT_EQ(scene.counts.manoeuvres, 0) << "off";
  }
}

}  // namespace
}  // namespace slammtt
