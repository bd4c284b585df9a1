// The Victoria Park reader, and the smoother on the first 300 keyframes of the recording
// (../shared/data/real/victoria_park; skipped with a reason when absent, as on a clean clone).
// The whole file against GTSAM is scripts/compare-victoria-park.py (docs/smoother.md).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "smoother/pose_landmark_dataset.h"
#include "smoother/smoother.h"

namespace slammtt {
namespace {

// ../shared beside the checkout (as CI lays it), or $SLAMMTT_SHARED_DIR (a git worktree
// elsewhere).
std::string VictoriaParkPath() {
  const char* shared = std::getenv("SLAMMTT_SHARED_DIR");
  return std::string(shared != nullptr ? shared : SLAMMTT_SOURCE_DIR "/../shared") +
         "/data/real/victoria_park/victoria_park.txt";
}

std::optional<PoseLandmarkDataset> LoadVictoriaPark() {
  std::ifstream in(VictoriaParkPath());
  if (!in) return std::nullopt;
  DatasetParseResult parsed = ParsePoseLandmarkDataset(in);
  EXPECT_TRUE(parsed.dataset) << parsed.error;
  return parsed.dataset;
}

DatasetParseResult Parse(const std::string& text) {
  std::istringstream in(text);
  return ParsePoseLandmarkDataset(in);
}

TEST(PoseLandmarkDatasetTest, ReadsKeyframesInFileOrder) {
  const DatasetParseResult parsed = Parse(
      "ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\n"
      "LANDMARK 1 7 3 4 0.4 0 0.4\n"
      "\n"
      "ODOMETRY 1 2 1 0 0.1 0.01 0 0 0.01 0 0.001\n"
      "LANDMARK 2 7 2 4 0.4 0.1 0.5\n");
  ASSERT_TRUE(parsed.dataset) << parsed.error;
  const PoseLandmarkDataset& d = *parsed.dataset;
  ASSERT_EQ(d.keyframes.size(), 3u);
  EXPECT_EQ(d.keyframes[0].pose, 0);
  EXPECT_FALSE(d.keyframes[0].odometry);
  EXPECT_EQ(d.keyframes[2].pose, 2);
  ASSERT_EQ(d.keyframes[2].observations.size(), 1u);
  EXPECT_EQ(d.observations[1].covariance(0, 1), 0.1);
  EXPECT_EQ(d.observations[1].covariance(1, 1), 0.5);
  EXPECT_EQ(d.odometry[1].covariance(2, 2), 0.001);
}

TEST(PoseLandmarkDatasetTest, MalformedLinesNameTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0\n", "line 1: ODOMETRY takes 11 numbers"},
      {"ODOMETRY 0 1 1 0 nan 0.01 0 0 0.01 0 0.001\n", "line 1: a number is not finite"},
      {"ODOMETRY 0 x 1 0 0 0.01 0 0 0.01 0 0.001\n", "line 1: pose ids"},
      {"VERTEX2 0 1 2 3\n", "line 1: unknown tag"},
      {"ODOMETRY 0 1 1 0 0 1 0 0 1 0 1\nODOMETRY 5 6 1 0 0 1 0 0 1 0 1\n",
       "line 2: odometry from pose 5 does not continue"},
      {"ODOMETRY 0 1 1 0 0 1 0 0 1 0 1\nODOMETRY 1 0 1 0 0 1 0 0 1 0 1\n",
       "line 2: pose 0 seen before"},
      {"ODOMETRY 0 1 1 0 0 1 0 0 1 0 1\nLANDMARK 0 9 1 1 1 0 1\n",
       "line 2: landmark seen from pose 0, not the latest"},
      {"LANDMARK 0 9 1 1 1 0\n", "line 1: LANDMARK takes 7 numbers"},
      {"", "no ODOMETRY or LANDMARK line"},
  };
  for (const auto& [text, expected] : cases) {
    const DatasetParseResult parsed = Parse(text);
    EXPECT_FALSE(parsed.dataset) << text;
    EXPECT_NE(parsed.error.find(expected), std::string::npos) << parsed.error;
  }
}

TEST(PoseLandmarkDatasetTest, NonPositiveDefiniteCovarianceIsRefusedWhenFed) {
  const DatasetParseResult parsed = Parse(
      "ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\n"
      "LANDMARK 1 7 3 4 0.4 0.9 0.4\n");
  ASSERT_TRUE(parsed.dataset);
  Smoother smoother;
  EXPECT_FALSE(AddKeyframe(*parsed.dataset, 0, LandmarkReading::kRelativePosition, &smoother));
  const auto error = AddKeyframe(*parsed.dataset, 1, LandmarkReading::kRelativePosition, &smoother);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("not positive definite"), std::string::npos) << *error;
}

// The first 300 keyframes (300 poses, 29 landmarks, 183 sightings) read as GTSAM's load2D reads
// them. GTSAM 4.3.0 (PyPI) on the same keyframes, with the same prior on pose 0 (sigma 1e-3):
// chi^2 = 2 * graph.error = 14.289149413329408 at the odometry chain and 3.146144243567121
// after LevenbergMarquardtOptimizer (7 iterations).
constexpr size_t kKeyframes = 300;
constexpr double kGtsamInitialChiSquare = 14.289149413329408;
constexpr double kGtsamOptimumChiSquare = 3.146144243567121;

TEST(VictoriaParkTest, BatchFromTheOdometryChainReachesGtsamsOptimum) {
  const auto dataset = LoadVictoriaPark();
  if (!dataset) GTEST_SKIP() << "no " << VictoriaParkPath() << " (../shared absent)";
  ASSERT_EQ(dataset->keyframes.size(), 6969u);
  ASSERT_EQ(dataset->observations.size(), 3640u);
  Smoother smoother;
  for (size_t k = 0; k < kKeyframes; ++k) {
    ASSERT_FALSE(AddKeyframe(*dataset, k, LandmarkReading::kBearingRange, &smoother));
  }
  EXPECT_EQ(smoother.num_landmarks(), 29);
  const SolveReport report = smoother.Optimize();
  ASSERT_TRUE(report.ok) << report.error;
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR(report.initial_chi_square, kGtsamInitialChiSquare, 1e-9 * kGtsamInitialChiSquare);
  EXPECT_NEAR(report.chi_square, kGtsamOptimumChiSquare, 1e-6 * kGtsamOptimumChiSquare);
}

// With GTSAM's Pose2 retraction the steps are GTSAM's too: the same optimum to rounding. (The
// whole file from its odometry chain: scripts/compare-victoria-park.py, docs/smoother.md.)
TEST(VictoriaParkTest, ExponentialPoseUpdateReachesGtsamsOptimumToRounding) {
  const auto dataset = LoadVictoriaPark();
  if (!dataset) GTEST_SKIP() << "no " << VictoriaParkPath() << " (../shared absent)";
  SmootherOptions options;
  options.pose_update = SmootherOptions::PoseUpdate::kExponential;
  Smoother smoother(options);
  for (size_t k = 0; k < kKeyframes; ++k) {
    ASSERT_FALSE(AddKeyframe(*dataset, k, LandmarkReading::kBearingRange, &smoother));
  }
  const SolveReport report = smoother.Optimize();
  ASSERT_TRUE(report.ok) << report.error;
  EXPECT_TRUE(report.converged);
  EXPECT_NEAR(report.chi_square, kGtsamOptimumChiSquare, 1e-12 * kGtsamOptimumChiSquare);
}

TEST(VictoriaParkTest, IncrementalPoseByPoseReachesTheSameOptimum) {
  const auto dataset = LoadVictoriaPark();
  if (!dataset) GTEST_SKIP() << "no " << VictoriaParkPath() << " (../shared absent)";
  Smoother smoother;
  SolveReport report;
  int refactorizations = 0;
  for (size_t k = 0; k < kKeyframes; ++k) {
    ASSERT_FALSE(AddKeyframe(*dataset, k, LandmarkReading::kBearingRange, &smoother));
    report = smoother.Update();
    ASSERT_TRUE(report.ok) << "keyframe " << k << ": " << report.error;
    refactorizations += report.refactorized ? 1 : 0;
  }
  EXPECT_LT(refactorizations, 30);  // most keyframes by rank updates of the kept factor
  EXPECT_NEAR(report.chi_square, kGtsamOptimumChiSquare, 1e-6 * kGtsamOptimumChiSquare);
  const Eigen::Matrix3d last = *smoother.PoseCovariance(dataset->keyframes[kKeyframes - 1].pose);
  EXPECT_TRUE(last.allFinite());
  EXPECT_GT(last.determinant(), 0.0);
}

TEST(VictoriaParkTest, RelativePositionReadingAlsoConverges) {
  const auto dataset = LoadVictoriaPark();
  if (!dataset) GTEST_SKIP() << "no " << VictoriaParkPath() << " (../shared absent)";
  Smoother batch;
  Smoother incremental;
  SolveReport last;
  for (size_t k = 0; k < kKeyframes; ++k) {
    ASSERT_FALSE(AddKeyframe(*dataset, k, LandmarkReading::kRelativePosition, &batch));
    ASSERT_FALSE(AddKeyframe(*dataset, k, LandmarkReading::kRelativePosition, &incremental));
    last = incremental.Update();
    ASSERT_TRUE(last.ok) << last.error;
  }
  const SolveReport report = batch.Optimize();
  ASSERT_TRUE(report.ok) << report.error;
  EXPECT_TRUE(report.converged);
  EXPECT_LT(report.chi_square, report.initial_chi_square);
  EXPECT_NEAR(last.chi_square, report.chi_square, 1e-6 * report.chi_square);
}

}  // namespace
}  // namespace slammtt
