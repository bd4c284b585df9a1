// What the association levels share (estimator/association.h): the assignment, ApplyPairs
// (gated once more at the current state, one-to-one, the budget respected) and the greedy
// one-to-one choice by NIS or by cost.
#include "estimator/association.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/estimator/step_scene.h"

namespace slammtt {
namespace {

using testing::StepScene;

TEST(AssignmentTest, RecordsBothDirections) {
  Assignment a(3, 2);
  EXPECT_EQ(a.num_measurements(), 3);
  EXPECT_EQ(a.num_objects(), 2);
  a.Set(2, 1);
  EXPECT_FALSE(a.MeasurementFree(2));
  EXPECT_FALSE(a.ObjectFree(1));
  EXPECT_TRUE(a.MeasurementFree(0));
  EXPECT_TRUE(a.ObjectFree(0));
  EXPECT_EQ(a.ObjectOf(2), 1);
  EXPECT_EQ(a.ObjectOf(0), -1);
  EXPECT_FALSE(a.PairFree({2, 0, 0.0}));
  EXPECT_FALSE(a.PairFree({0, 1, 0.0}));
  EXPECT_TRUE(a.PairFree({0, 0, 0.0}));
}

TEST(ApplyPairsTest, UpdatesWithTheGatedFreePairsAndAssignsThem) {
  StepScene scene;
  const int near = scene.AddLandmark({4.0, 0.0}, 0.1);
  const int far = scene.AddLandmark({0.0, 6.0}, 0.1);
  const int z_near = scene.Measure({4.05, 0.0});
  const int z_far = scene.Measure({0.0, 9.0});  // 3 m away from its landmark: out of any gate
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, 7 * testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  Assignment assignment(2, 2);
  const double x_before = scene.state.position(near)(0);
  const int applied = ApplyPairs({{z_near, near, 0.0}, {z_far, far, 0.0}}, 9.21, scan,
                                 scene.options, &predicted, &scene.state, &assignment,
                                 &scene.counts);
  EXPECT_EQ(applied, 1);
  EXPECT_EQ(assignment.ObjectOf(z_near), near);
  EXPECT_TRUE(assignment.MeasurementFree(z_far)) << "outside the gate: not associated";
  EXPECT_GT(scene.state.position(near)(0), x_before + 0.02) << "the update moved it";
  EXPECT_EQ(scene.state.object(near).record.last_update_utime, 7 * testing::kSecond);
  EXPECT_EQ(scene.state.object(far).record.last_update_utime, 0);
  // A pair whose measurement or object is taken is not applied again.
  EXPECT_EQ(ApplyPairs({{z_near, near, 0.0}}, 9.21, scan, scene.options, &predicted,
                       &scene.state, &assignment, &scene.counts),
            0);
}

TEST(ApplyPairsTest, AnObjectOverTheBudgetIsAssociatedWithoutUpdating) {
  StepScene scene;
  const int landmark = scene.AddLandmark({4.0, 0.0}, 0.1);
  const int z = scene.Measure({4.05, 0.0});
  const std::vector<uint8_t> may_update = {0};
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  Assignment assignment(1, 1);
  const Eigen::VectorXd mean_before = scene.state.mean();
  EXPECT_EQ(ApplyPairs({{z, landmark, 0.0}}, 9.21, scan, scene.options, &predicted,
                       &scene.state, &assignment, &scene.counts),
            0);
  EXPECT_EQ(assignment.ObjectOf(z), landmark);
  EXPECT_EQ(scene.counts.static_updates_skipped, 1);
  EXPECT_EQ(scene.state.mean(), mean_before);
  EXPECT_EQ(scene.state.object(landmark).record.last_update_utime, 0);
}

TEST(ApplyPairsTest, GatesAtTheStateTheEarlierPairsLeft) {
  // Two measurements of one landmark: the first pair updates it, so the second one is judged
  // against the updated (much tighter) estimate and fails a gate it would pass before.
  StepScene scene;
  const int landmark = scene.AddLandmark({4.0, 0.0}, 0.3);
  const int z1 = scene.Measure({4.0, 0.0}, 0.01, 0.002);
  scene.AddLandmark({8.0, 0.0}, 0.3);
  const int z2 = scene.Measure({4.3, 0.0}, 0.01, 0.002);
  ASSERT_LT(scene.Nis(z2, landmark), 9.21) << "compatible before the first update";
  const std::vector<uint8_t> may_update = scene.AllMayUpdate();
  const ScanAssociation scan{scene.measurements, may_update, testing::kSecond};
  ObservationPredictions predicted(scene.options.sensor);
  Assignment assignment(2, 2);
  ApplyPairs({{z1, landmark, 0.0}}, 9.21, scan, scene.options, &predicted, &scene.state,
             &assignment, &scene.counts);
  Assignment other(2, 2);
  EXPECT_EQ(ApplyPairs({{z2, landmark, 0.0}}, 9.21, scan, scene.options, &predicted,
                       &scene.state, &other, &scene.counts),
            0);
  EXPECT_TRUE(other.MeasurementFree(z2));
}

TEST(GreedyOneToOneTest, TakesPairsInIncreasingNisOrCost) {
  // Measurement 0 is nearer object 0 by the NIS, nearer object 1 by the cost.
  const std::vector<Candidate> pairs = {{0, 0, 1.0, 9.0}, {0, 1, 2.0, 3.0}, {1, 1, 1.5, 4.0},
                                        {1, 0, 3.0, 5.0}};
  const Assignment none(2, 2);
  const std::vector<Candidate> by_nis = GreedyOneToOne(pairs, none, PairOrder::kByNis);
  ASSERT_EQ(by_nis.size(), 2u);
  EXPECT_EQ(by_nis[0].measurement, 0);
  EXPECT_EQ(by_nis[0].object, 0);
  EXPECT_EQ(by_nis[1].measurement, 1);
  EXPECT_EQ(by_nis[1].object, 1);
  const std::vector<Candidate> by_cost = GreedyOneToOne(pairs, none, PairOrder::kByCost);
  ASSERT_EQ(by_cost.size(), 2u);
  EXPECT_EQ(by_cost[0].measurement, 0);
  EXPECT_EQ(by_cost[0].object, 1);
  EXPECT_EQ(by_cost[1].measurement, 1);
  EXPECT_EQ(by_cost[1].object, 0);
  // What is taken already stays out.
  Assignment taken(2, 2);
  taken.Set(0, 0);
  const std::vector<Candidate> rest = GreedyOneToOne(pairs, taken, PairOrder::kByNis);
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0].measurement, 1);
  EXPECT_EQ(rest[0].object, 1);
}

}  // namespace
}  // namespace slammtt
