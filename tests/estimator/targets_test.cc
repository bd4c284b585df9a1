// The accuracy targets of the estimator's issue, on the shipped scenarios, seeds 1 to 5, scored
// by slammtt-eval (label `target`; docs/estimator.md has the measured figures). A target that
// is missed fails here; the failure message carries every figure.
#include <gtest/gtest.h>

#include <iostream>
#include <map>

#include "tests/estimator/pipeline_runner.h"

namespace slammtt {
namespace {

using nlohmann::json;
using testing::Headline;
using testing::PipelineRun;
using testing::PipelineRunner;

constexpr int kSeeds[] = {1, 2, 3, 4, 5};

double Number(const json& report, const char* key) {
  if (!report.contains(key) || !report[key].is_number()) {
    ADD_FAILURE() << "report has no number " << key;
    return std::numeric_limits<double>::quiet_NaN();
  }
  return report[key].get<double>();
}

void Print(const std::string& what, const PipelineRun& run) {
  std::cout << what << ": " << Headline(run.report) << "hypotheses " << run.hypotheses << "\n";
}

// Classification details: movers' delays and the share of static objects labelled static.
struct ClassificationFigures {
  std::vector<double> mover_delays_s;  // NaN when a mover never settled on "moving"
  int statics = 0;
  int statics_labelled_static = 0;
};

ClassificationFigures Classification(const json& report) {
  ClassificationFigures figures;
  const json& objects = report["detail"]["classification"]["objects"];
  for (const json& o : objects) {
    if (o["true_class"] == "moving") {
      figures.mover_delays_s.push_back(o["delay_s"].is_number()
                                           ? o["delay_s"].get<double>()
                                           : std::numeric_limits<double>::quiet_NaN());
    } else {
      ++figures.statics;
      if (o["final_label"] == "static") ++figures.statics_labelled_static;
    }
  }
  return figures;
}

TEST(EstimatorTargetsTest, S1CrossingPointFeatures) {
  PipelineRunner runner;
  for (int seed : kSeeds) {
    SCOPED_TRACE("s1-crossing seed " + std::to_string(seed));
    const PipelineRun ml = runner.Run("s1-crossing", seed, "ml_ransac");
    const PipelineRun nn = runner.Run("s1-crossing", seed, "static_nn");
    const PipelineRun all = runner.Run("s1-crossing", seed, "ransac_all_pairs");
    Print("s1-crossing seed " + std::to_string(seed) + " ml_ransac", ml);
    Print("s1-crossing seed " + std::to_string(seed) + " static_nn", nn);
    Print("s1-crossing seed " + std::to_string(seed) + " ransac_all_pairs", all);
    const json& r = ml.report;
    EXPECT_EQ(Number(r, "id_switches"), 0.0);
    EXPECT_GE(Number(r, "mota"), 0.95);
    EXPECT_LE(Number(r, "ate_rmse_m"), 0.3);
    EXPECT_LE(5.0 * Number(r, "ate_rmse_m"), Number(nn.report, "ate_rmse_m"))
        << "robot ATE not 5 times lower than the static-world baseline";
    EXPECT_EQ(Number(r, "movers_in_static_map"), 0.0);
    EXPECT_GE(Number(nn.report, "movers_in_static_map"), 1.0)
        << "the static-world baseline should map movers as static (paper Fig. 5)";
    const ClassificationFigures c = Classification(r);
    EXPECT_EQ(c.mover_delays_s.size(), 5u);
    for (double delay : c.mover_delays_s) {
      EXPECT_LE(delay, 2.0) << "a mover was labelled moving later than 2 s after first sighting";
    }
    EXPECT_GE(c.statics_labelled_static, 0.95 * c.statics)
        << c.statics_labelled_static << " of " << c.statics << " static objects labelled static";
    EXPECT_LE(10 * ml.hypotheses, all.hypotheses)
        << "ML-RANSAC " << ml.hypotheses << " hypotheses, plain RANSAC " << all.hypotheses;
  }
}

TEST(EstimatorTargetsTest, S2LobbyFullPipeline) {
  PipelineRunner runner;
  for (int seed : kSeeds) {
    SCOPED_TRACE("s2-lobby seed " + std::to_string(seed));
    const PipelineRun ml = runner.Run("s2-lobby", seed, "ml_ransac");
    const PipelineRun all = runner.Run("s2-lobby", seed, "ransac_all_pairs");
    Print("s2-lobby seed " + std::to_string(seed) + " ml_ransac", ml);
    Print("s2-lobby seed " + std::to_string(seed) + " ransac_all_pairs", all);
    EXPECT_GE(Number(ml.report, "mota"), 0.85);
    EXPECT_LE(10 * ml.hypotheses, all.hypotheses)
        << "ML-RANSAC " << ml.hypotheses << " hypotheses, plain RANSAC " << all.hypotheses;
  }
}

TEST(EstimatorTargetsTest, S3NoStaticObjects) {
  PipelineRunner runner;
  for (int seed : kSeeds) {
    SCOPED_TRACE("s3-no-static seed " + std::to_string(seed));
    const PipelineRun ml = runner.Run("s3-no-static", seed, "ml_ransac");
    Print("s3-no-static seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_GE(Number(ml.report, "mota"), 0.9);
    EXPECT_LE(Number(ml.report, "ate_rmse_m"), 1.1 * Number(ml.report, "odometry_ate_rmse_m"))
        << "the robot estimate is more than 10 % worse than odometry alone";
  }
}

TEST(EstimatorTargetsTest, RplidarA2FullPipeline) {
  PipelineRunner runner;
  for (int seed : kSeeds) {
    SCOPED_TRACE("rplidar-a2 seed " + std::to_string(seed));
    const PipelineRun ml = runner.Run("rplidar-a2", seed, "ml_ransac");
    Print("rplidar-a2 seed " + std::to_string(seed) + " ml_ransac", ml);
    EXPECT_GE(Number(ml.report, "mota"), 0.85);
  }
}

// No target yet: every figure is printed (and checked to exist) for the note.
TEST(EstimatorTargetsTest, CrowdZara02FullPipeline) {
  PipelineRunner runner;
  for (int seed : kSeeds) {
    SCOPED_TRACE("crowd-zara02 seed " + std::to_string(seed));
    const PipelineRun ml = runner.Run("crowd-zara02", seed, "ml_ransac");
    Print("crowd-zara02 seed " + std::to_string(seed) + " ml_ransac", ml);
    const json& c = ml.report["detail"]["classification"];
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
