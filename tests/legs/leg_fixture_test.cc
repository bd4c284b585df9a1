// The committed fixture (tests/data/leg_tracker/positive_1_extracted_first20.lcm: 20 scans and
// 30 labelled legs of positive_1_extracted, BSD 3-Clause, Angus Leigh) through the default
// segmenter and its trained leg classifier. Always runs (no ../shared, no venv needed). These
// scans are training data of the classifier: the floors guard against regressions; the
// held-out figures are real_legs_test.cc's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tools/legs/leg_training.h"
#include "tools/legs/recording_log.h"

namespace slammtt {
namespace {

// Measured with the committed model.
constexpr int64_t kFixtureLegsFoundFloor = 19;  // measured: 19 of 30
constexpr double kFixturePrecisionFloor = 0.99;  // measured: 1.0

const char kFixture[] = SLAMMTT_SOURCE_DIR "/tests/data/leg_tracker/positive_1_extracted_first20.lcm";

TEST(LegFixtureTest, LabelledLegsOfTheFixtureAreFound) {
  const Recording r = ReadRecording("fixture", kFixture);
  ASSERT_EQ(r.scans.size(), 20u);
  EXPECT_EQ(r.undecodable, 0);
  EXPECT_EQ(r.labels_without_scan, 0);
  const LegDetectionScore s = EvaluateRecording(r, SegmenterOptions{}, 1, LabelArc{});
  EXPECT_EQ(s.labels, 30);
  EXPECT_GE(s.labels_found, kFixtureLegsFoundFloor) << "of " << s.labels;
  EXPECT_GE(s.precision(), kFixturePrecisionFloor);
}

TEST(LegFixtureTest, EveryEvaluatedClusterIsRecordedWithFiniteFeatures) {
  const Recording r = ReadRecording("fixture", kFixture);
  Segmenter segmenter(SegmenterOptions{});
  for (const RecordedScan& scan : r.scans) {
    segmenter.Segment(scan.view());
    ASSERT_FALSE(segmenter.leg_clusters().empty());
    for (const Feature& f : segmenter.features()) {
      ASSERT_GE(f.leg_cluster, 0);
      ASSERT_LT(static_cast<size_t>(f.leg_cluster), segmenter.leg_clusters().size());
      EXPECT_EQ(f.leg_likeness,
                segmenter.leg_clusters()[static_cast<size_t>(f.leg_cluster)].leg_likeness);
    }
    for (const LegClusterRecord& c : segmenter.leg_clusters()) {
      for (float v : c.features) EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(c.leg_likeness, 0.0);
      EXPECT_LE(c.leg_likeness, 1.0);
    }
  }
}

TEST(LegFixtureTest, DecimatedScansKeepEveryKthBeamAndTheLabels) {
  const Recording r = ReadRecording("fixture", kFixture);
  const RecordedScan d = Decimate(r.scans[0], 3);
  ASSERT_EQ(d.angle_rad.size(), (r.scans[0].angle_rad.size() + 2) / 3);
  EXPECT_EQ(d.angle_rad[1], r.scans[0].angle_rad[3]);
  EXPECT_EQ(d.range_m[2], r.scans[0].range_m[6]);
  EXPECT_EQ(d.labels_m.size(), r.scans[0].labels_m.size());
}

}  // namespace
}  // namespace slammtt
