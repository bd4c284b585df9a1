// The perception targets of issue 11 not met yet on synthetic offices (label target_open; left
// out of the default run; tests/perception/office_figures.h).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/perception/office_figures.h"

namespace slammtt {
namespace {

using testing_support::Figures;
using testing_support::Measure;
using testing_support::Percentile;

// Targets not met yet (label target_open, docs/targets.md): person recall at 0.35 degrees on the
// held-out seeds (0.879), person precision at 0.35 degrees (0.871 on seeds 1-20, 0.868 on
// 21-40; 0.879 / 0.878 before max_leg_separation_m became 0.7), and no point feature on a wall
// (4-10 % are).
TEST(PerceptionFiguresTest, OpenTargets) {
  for (uint64_t first_seed : {1, 21}) {
    SCOPED_TRACE(first_seed);
    const Figures hokuyo = Measure(0.35, 12.0, first_seed);
    EXPECT_GE(hokuyo.pooled.PersonRecall(), 0.9);
    EXPECT_GE(hokuyo.pooled.PersonPrecision(), 0.9);
    EXPECT_EQ(hokuyo.pooled.point_features_on_walls, 0);
    const Figures rplidar = Measure(0.9, 4.0, first_seed);
    EXPECT_EQ(rplidar.pooled.point_features_on_walls, 0);
  }
}

}  // namespace
}  // namespace slammtt
