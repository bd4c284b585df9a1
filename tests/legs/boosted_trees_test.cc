// Gradient-boosted trees (tools/legs/boosted_trees.h): they learn, they are deterministic to
// the byte, and the generated source holds what was trained.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

#include "tools/legs/boosted_trees.h"

namespace slammtt {
namespace {

// Legs: width 0.08-0.2 m and convexity above 0.3; others anything else; noise features random.
std::vector<TrainingSample> Samples(uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<TrainingSample> samples;
  for (int i = 0; i < n; ++i) {
    TrainingSample s;
    for (float& f : s.features) f = u(rng);
    s.features[kWidth] = 0.5f * u(rng);
    s.features[kConvexity] = u(rng);
    s.leg = s.features[kWidth] > 0.08f && s.features[kWidth] < 0.2f &&
            s.features[kConvexity] > 0.3f;
    samples.push_back(s);
  }
  return samples;
}

double Accuracy(const TrainedTrees& trees, const std::vector<TrainingSample>& samples) {
  const LegModel model = trees.model();
  int right = 0;
  for (const TrainingSample& s : samples) right += (LegProbability(model, s.features) >= 0.5) == s.leg;
  return static_cast<double>(right) / static_cast<double>(samples.size());
}

TEST(BoostedTreesTest, LearnsARuleAndGeneralisesToNewSamples) {
  BoostingOptions options;
  options.rounds = 60;
  const TrainedTrees trees = TrainBoostedTrees(Samples(1, 4000), options);
  EXPECT_STREQ(CheckLegModel(trees.model()), "");
  EXPECT_EQ(trees.roots.size(), 60u);
  EXPECT_GT(Accuracy(trees, Samples(2, 4000)), 0.98);  // samples it never saw
}

TEST(BoostedTreesTest, SameSamplesGiveTheSameBytes) {
  BoostingOptions options;
  options.rounds = 20;
  const std::vector<TrainingSample> samples = Samples(3, 2000);
  const std::string a = ModelSource(TrainBoostedTrees(samples, options), "provenance");
  const std::string b = ModelSource(TrainBoostedTrees(samples, options), "provenance");
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("// provenance\n"), std::string::npos);
  EXPECT_NE(a.find("const LegModel& TrainedLegModel()"), std::string::npos);
  BoostingOptions other = options;
  other.max_depth = 2;
  EXPECT_NE(a, ModelSource(TrainBoostedTrees(samples, other), "provenance"));
}

TEST(BoostedTreesTest, OneClassAloneIsRefused) {
  std::vector<TrainingSample> samples = Samples(4, 100);
  for (TrainingSample& s : samples) s.leg = false;
  EXPECT_THROW(TrainBoostedTrees(samples, BoostingOptions{}), std::invalid_argument);
  EXPECT_THROW(TrainBoostedTrees({}, BoostingOptions{}), std::invalid_argument);
}

TEST(BoostedTreesTest, ThresholdsSeparateNeighbouringValuesExactly) {
  // Two values one float step apart: the split must still put them on different sides.
  std::vector<TrainingSample> samples(40);
  for (size_t i = 0; i < samples.size(); ++i) {
    samples[i].leg = i % 2 == 0;
    samples[i].features[kRange] = samples[i].leg ? 1.0f : std::nextafter(1.0f, 2.0f);
  }
  BoostingOptions options;
  options.rounds = 5;
  options.min_child_samples = 1;
  const TrainedTrees trees = TrainBoostedTrees(samples, options);
  EXPECT_DOUBLE_EQ(Accuracy(trees, samples), 1.0);
}

}  // namespace
}  // namespace slammtt
