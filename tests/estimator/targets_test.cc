// The targets of the estimator's issue that the estimator meets on every seed (1 to 5) of the
// shipped scenarios, scored by slammtt-eval (label `target`, in the default run). Each TEST is
// one target or a group of targets that pass or fail together; a run (world -> replay -> eval)
// is made once and shared by the TESTs of this program. The targets not met yet are asserted,
// just as strictly, by targets_open_test.cc (label `target_open`); docs/targets.md lists them.
#include "tests/estimator/target_figures.h"

namespace slammtt {
namespace {

using testing::Classification;
using testing::ClassificationFigures;
using testing::kTargetSeeds;
using testing::Number;
using testing::Print;
using testing::TargetRun;

const testing::PipelineRun& S1(int seed, const char* mode = "ml_ransac") {
  return TargetRun("s1-crossing", seed, mode);
}

TEST(S1CrossingTargetsTest, NoIdentitySwitchThroughTheOcclusions) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    Print("s1-crossing seed " + std::to_string(seed) + " ml_ransac", S1(seed));
    EXPECT_EQ(Number(S1(seed).report, "id_switches"), 0.0);
  }
}

TEST(S1CrossingTargetsTest, MotaAtLeast095) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    EXPECT_GE(Number(S1(seed).report, "mota"), 0.95);
  }
}

TEST(S1CrossingTargetsTest, RobotAteAtMost03m) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    EXPECT_LE(Number(S1(seed).report, "ate_rmse_m"), 0.3);
  }
}

// ML-RANSAC keeps movers out of the static map; the static-world baseline (a) shows the
// paper's failure (Fig. 5): movers mapped as static.
TEST(S1CrossingTargetsTest, NoMoverInTheStaticMapWhileBaselineAMapsThem) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    Print("s1-crossing seed " + std::to_string(seed) + " static_nn", S1(seed, "static_nn"));
    EXPECT_EQ(Number(S1(seed).report, "movers_in_static_map"), 0.0);
    EXPECT_GE(Number(S1(seed, "static_nn").report, "movers_in_static_map"), 1.0)
        << "the static-world baseline should map movers as static (paper Fig. 5)";
  }
}

TEST(S1CrossingTargetsTest, EveryMoverLabelledMovingWithin2sOfFirstSighting) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    const ClassificationFigures c = Classification(S1(seed).report);
    EXPECT_EQ(c.mover_delays_s.size(), 5u);
    for (double delay : c.mover_delays_s) {
      std::cout << "s1-crossing seed " << seed << " mover delay " << delay << " s\n";
      EXPECT_LE(delay, 2.0) << "a mover was labelled moving later than 2 s after first sighting";
    }
  }
}

TEST(S1CrossingTargetsTest, AtLeast95PercentOfStaticLandmarksStaticAtTheEnd) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    const ClassificationFigures c = Classification(S1(seed).report);
    std::cout << "s1-crossing seed " << seed << ": " << c.statics_labelled_static << " of "
              << c.statics << " static objects labelled static\n";
    EXPECT_GT(c.statics, 0);
    EXPECT_GE(c.statics_labelled_static, 0.95 * c.statics);
  }
}

TEST(S1CrossingTargetsTest, TenTimesFewerHypothesesThanPlainRansac) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    const testing::PipelineRun& all = S1(seed, "ransac_all_pairs");
    Print("s1-crossing seed " + std::to_string(seed) + " ransac_all_pairs", all);
    EXPECT_LE(10 * S1(seed).hypotheses, all.hypotheses)
        << "ML-RANSAC " << S1(seed).hypotheses << " hypotheses, plain RANSAC " << all.hypotheses;
  }
}

TEST(S2LobbyTargetsTest, MotaAtLeast085) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s2-lobby seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("s2-lobby", seed, "ml_ransac");
    Print("s2-lobby seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_GE(Number(ml.report, "mota"), 0.85);
  }
}

TEST(S2LobbyTargetsTest, TenTimesFewerHypothesesThanPlainRansac) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s2-lobby seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("s2-lobby", seed, "ml_ransac");
    const testing::PipelineRun& all = TargetRun("s2-lobby", seed, "ransac_all_pairs");
    Print("s2-lobby seed " + std::to_string(seed) + " ml_ransac", ml);
    Print("s2-lobby seed " + std::to_string(seed) + " ransac_all_pairs", all);
    EXPECT_LE(10 * ml.hypotheses, all.hypotheses)
        << "ML-RANSAC " << ml.hypotheses << " hypotheses, plain RANSAC " << all.hypotheses;
  }
}

TEST(S3NoStaticTargetsTest, EveryMoverTrackedMotaAtLeast09) {
  // Met since the odometry's heading drift is a state of the EKF (docs/estimator.md).
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s3-no-static seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("s3-no-static", seed, "ml_ransac");
    Print("s3-no-static seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_GE(Number(ml.report, "mota"), 0.9);
  }
}

TEST(S3NoStaticTargetsTest, RobotNeverMoreThan10PercentWorseThanOdometry) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("s3-no-static seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("s3-no-static", seed, "ml_ransac");
    Print("s3-no-static seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_LE(Number(ml.report, "ate_rmse_m"), 1.1 * Number(ml.report, "odometry_ate_rmse_m"))
        << "the robot estimate is more than 10 % worse than odometry alone";
  }
}

TEST(RplidarA2TargetsTest, MotaAtLeast085) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("rplidar-a2 seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("rplidar-a2", seed, "ml_ransac");
    Print("rplidar-a2 seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_GE(Number(ml.report, "mota"), 0.85);
  }
}

// No target yet: every figure is printed (and checked to exist) for the note.
TEST(CrowdZara02FiguresTest, EveryFigureComesFromTheShippedEvaluation) {
  for (int seed : kTargetSeeds) {
    SCOPED_TRACE("crowd-zara02 seed " + std::to_string(seed));
    const testing::PipelineRun& ml = TargetRun("crowd-zara02", seed, "ml_ransac");
    Print("crowd-zara02 seed " + std::to_string(seed) + " ml_ransac", ml);
    const nlohmann::json& c = ml.report["detail"]["classification"];
    std::cout << "  classification: mean delay " << c["mean_delay_s"].dump() << " s, max "
              << c["max_delay_s"].dump() << " s, confusion "
              << c["confusion_true_by_final"].dump() << "\n";
    for (const char* key : {"ate_rmse_m", "mota", "ospa_mean_m", "classification_accuracy"}) {
      EXPECT_TRUE(std::isfinite(Number(ml.report, key))) << key;
    }
  }
}

}  // namespace
}  // namespace slammtt
