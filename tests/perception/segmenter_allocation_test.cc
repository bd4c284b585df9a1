// Segmenter::Segment() does not allocate once its buffers have grown to the largest scan seen
// (segmenter.h). Counted with a replaced global operator new in this test program.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "perception/segmenter.h"
#include "tests/perception/synthetic_scan.h"

namespace {
std::atomic<int64_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  void* p = std::malloc(size > 0 ? size : 1);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace slammtt {
namespace {

using testing_support::CastScan;
using testing_support::Circle;
using testing_support::EvenAngles;

TEST(SegmenterAllocationTest, SegmentDoesNotAllocateAfterWarmUp) {
  {  // the counter sees allocations
    const int64_t before = g_allocations.load();
    std::vector<int> probe(10);
    EXPECT_EQ(g_allocations.load() - before, 1);
  }
  std::mt19937_64 rng(1);
  const std::vector<Circle> scene = {{2.0, 0.5, 0.2}, {-1.5, 2.5, 0.25}, {0.5, -3.0, 0.15},
                                     {-3.0, -1.0, 0.3}, {4.0, 3.0, 0.2}, {2.4, 0.9, 0.2}};
  const testing_support::TestScan big =
      CastScan(scene, EvenAngles(-M_PI, 2.0 * M_PI, 1600, true), 12.0, 0.01, &rng);
  const testing_support::TestScan small =
      CastScan(scene, EvenAngles(0.0, 2.0 * M_PI, 400, true), 12.0, 0.01, &rng);
  testing_support::TestScan shuffled = big;
  std::vector<size_t> order(big.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  for (size_t i = 0; i < order.size(); ++i) {
    shuffled.angle_rad[i] = big.angle_rad[order[i]];
    shuffled.range_m[i] = big.range_m[order[i]];
    shuffled.valid[i] = big.valid[order[i]];
  }
  for (CentreRule rule :
       {CentreRule::kMiddlePoint, CentreRule::kRadiusCorrected, CentreRule::kCircleFit}) {
    SegmenterOptions options;
    options.centre_rule = rule;
    Segmenter segmenter(options);
    segmenter.Segment(big.View());  // warm-up: the buffers grow here
    segmenter.Segment(shuffled.View());
    const int64_t before = g_allocations.load();
    size_t features = 0;
    for (int i = 0; i < 5; ++i) {
      features += segmenter.Segment(big.View()).size();
      features += segmenter.Segment(small.View()).size();
      features += segmenter.Segment(shuffled.View()).size();
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << CentreRuleName(rule);
    EXPECT_EQ(features, 15u * scene.size()) << CentreRuleName(rule);
  }
}

}  // namespace
}  // namespace slammtt
