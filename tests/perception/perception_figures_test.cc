// The perception figures of issue 11 (Measure) on synthetic offices that meet their targets on
// seeds 1-20 and on the held-out seeds 21-40 (tests/perception/office_figures.h; label target).
// The 0.35-degree person precision (0.871 / 0.868 with the trained classifier) is open
// (perception_figures_open_test.cc).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/perception/office_figures.h"

namespace slammtt {
namespace {

using testing_support::Figures;
using testing_support::Measure;
using testing_support::Percentile;

// Targets met on both seed sets (label target).
TEST(PerceptionFiguresTest, MetTargets) {
  for (uint64_t first_seed : {1, 21}) {
    SCOPED_TRACE(first_seed);
    const Figures hokuyo = Measure(0.35, 12.0, first_seed);
    // Recall at 0.35 degrees: met on the tuning seeds only (0.903; held out 0.879, open).
    if (first_seed == 1) {
      EXPECT_GE(hokuyo.pooled.PersonRecall(), 0.9);
    }
    EXPECT_LE(Percentile(hokuyo.pooled.centre_errors_m, 0.5), 0.08);
    const Figures rplidar = Measure(0.9, 4.0, first_seed);
    EXPECT_GE(rplidar.pooled.PersonRecall(), 0.8);
    EXPECT_GE(rplidar.pooled.PersonPrecision(), 0.9);
    EXPECT_LE(Percentile(rplidar.pooled.centre_errors_m, 0.5), 0.08);
    // Lines: the walls' angles within a degree, distances within 3 cm (medians).
    for (const Figures* f : {&hokuyo, &rplidar}) {
      EXPECT_GT(f->pooled.lines_matched, 0.99 * static_cast<double>(f->pooled.lines));
      EXPECT_LT(Percentile(f->pooled.line_angle_errors_rad, 0.5), M_PI / 180.0);
      EXPECT_LT(Percentile(f->pooled.line_distance_errors_m, 0.5), 0.03);
    }
  }
}

}  // namespace
}  // namespace slammtt
