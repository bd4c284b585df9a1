#include "tools/metrics/classification_score.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace slammtt {
namespace {

constexpr int64_t kScanUs = 125000;  // 8 scans per second

TruthObject Truth(int64_t id, double x, ObjectLabel true_class, bool visible = true,
                  bool standing = false) {
  return TruthObject{id, Eigen::Vector2d(x, 0), true_class, visible, standing};
}
LabelledTrack Track(int64_t id, double x, ObjectLabel label) {
  return LabelledTrack{id, Eigen::Vector2d(x, 0.1), label};
}

TEST(ClassificationTest, DelayIsUntilTheLabelStaysRight) {
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  const auto M = ObjectLabel::kMoving;
  const auto U = ObjectLabel::kUndecided;
  // Object 1 (static): undecided, undecided, static, static.
  // Object 2 (moving): moving, static, moving, moving  -> settles at scan 2.
  const std::vector<ObjectLabel> labels1 = {U, U, S, S};
  const std::vector<ObjectLabel> labels2 = {M, S, M, M};
  for (int k = 0; k < 4; ++k) {
    acc.AddScan(k * kScanUs, {Truth(1, 0, S), Truth(2, 10, M)},
                {Track(50, 0, labels1[k]), Track(60, 10, labels2[k])});
  }
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].final_label, S);
  EXPECT_DOUBLE_EQ(*s.objects[0].delay_s, 2 * kScanUs * 1e-6);
  EXPECT_EQ(s.objects[1].final_label, M);
  EXPECT_DOUBLE_EQ(*s.objects[1].delay_s, 2 * kScanUs * 1e-6);
  EXPECT_DOUBLE_EQ(*s.accuracy, 1.0);
  EXPECT_DOUBLE_EQ(*s.mean_delay_s, 0.25);
  EXPECT_EQ(s.confusion[0][0], 1);
  EXPECT_EQ(s.confusion[1][1], 1);
}

TEST(ClassificationTest, DelayCountsFromFirstSightingAndIgnoresUnmatchedScans) {
  ClassificationAccumulator acc(1.0);
  const auto M = ObjectLabel::kMoving;
  acc.AddScan(0, {Truth(1, 0, M)}, {});                   // seen, no track yet
  acc.AddScan(kScanUs, {Truth(1, 0, M)}, {Track(7, 0, M)});
  acc.AddScan(2 * kScanUs, {Truth(1, 0, M)}, {});         // track missing: no label, no reset
  acc.AddScan(3 * kScanUs, {Truth(1, 0, M)}, {Track(7, 0, M)});
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].num_matched_scans, 2);
  EXPECT_DOUBLE_EQ(*s.objects[0].delay_s, kScanUs * 1e-6);
  EXPECT_EQ(*s.objects[0].visible_scans_until_right, 1);
}

TEST(ClassificationTest, CountsVisibleScansBeforeTheLabelSettles) {
  // Seen once at scan 0 (undecided), out of view for 100 scans, then static from scan 102 on:
  // a delay of 102 scans of time but only 2 visible scans.
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  acc.AddScan(0, {Truth(1, 0, S)}, {Track(7, 0, ObjectLabel::kUndecided)});
  for (int k = 1; k <= 100; ++k) acc.AddScan(k * kScanUs, {Truth(1, 0, S, false)}, {});
  acc.AddScan(101 * kScanUs, {Truth(1, 0, S)}, {Track(7, 0, ObjectLabel::kUndecided)});
  acc.AddScan(102 * kScanUs, {Truth(1, 0, S)}, {Track(7, 0, S)});
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_DOUBLE_EQ(*s.objects[0].delay_s, 102 * kScanUs * 1e-6);
  EXPECT_EQ(*s.objects[0].visible_scans_until_right, 2);
  EXPECT_DOUBLE_EQ(*s.mean_visible_scans_until_right, 2.0);
}

TEST(ClassificationTest, WrongAndUntrackedObjects) {
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  const auto M = ObjectLabel::kMoving;
  // Object 1 (moving) ends labelled static: wrong, no delay. Object 2 (static) never tracked.
  // Object 3 is never visible: not scored even though a track sits on it.
  acc.AddScan(0, {Truth(1, 0, M), Truth(2, 20, S), Truth(3, 40, S, false)},
              {Track(5, 0, M), Track(6, 40, S)});
  acc.AddScan(kScanUs, {Truth(1, 0, M), Truth(2, 20, S), Truth(3, 40, S, false)},
              {Track(5, 0, S), Track(6, 40, S)});
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_FALSE(s.objects[0].correct);
  EXPECT_FALSE(s.objects[0].delay_s.has_value());
  EXPECT_FALSE(s.objects[1].final_label.has_value());
  EXPECT_EQ(s.confusion[1][0], 1);                  // moving labelled static
  EXPECT_EQ(s.confusion[0][kUntrackedColumn], 1);   // static never tracked
  EXPECT_DOUBLE_EQ(*s.accuracy, 0.0);
  EXPECT_DOUBLE_EQ(*s.accuracy_of_tracked, 0.0);
  EXPECT_FALSE(s.mean_delay_s.has_value());
}

TEST(ClassificationTest, AMoverThatStandsThenWalksIsJudgedOnlyWhileItWalks) {
  // Object 1 (a mover) stands at scans 0-3, labelled static by the estimator (right: a post is
  // what it looks like); it walks from scan 4: undecided at 4, moving from 5 on; it stops again
  // at scans 8-9 and the estimator, rightly, calls it static again.
  // First sighting = scan 4 (first scan visible while moving); the standing scans carry no
  // label; final label = the label at the last judged scan (7): moving, so right; delay =
  // scan 5 - scan 4; one visible judged scan (4) before it settled.
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  const auto M = ObjectLabel::kMoving;
  const auto U = ObjectLabel::kUndecided;
  const std::vector<ObjectLabel> labels = {S, S, S, S, U, M, M, M, S, S};
  for (int k = 0; k < 10; ++k) {
    const bool standing = k < 4 || k >= 8;
    acc.AddScan(k * kScanUs, {Truth(1, 0, M, true, standing)}, {Track(7, 0, labels[k])});
  }
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 1u);
  const ObjectClassification& o = s.objects[0];
  EXPECT_EQ(o.first_visible_utime, 4 * kScanUs);
  EXPECT_EQ(o.num_matched_scans, 4);
  EXPECT_EQ(o.final_label, M);
  EXPECT_TRUE(o.correct);
  EXPECT_DOUBLE_EQ(*o.delay_s, kScanUs * 1e-6);
  EXPECT_EQ(*o.visible_scans_until_right, 1);
  EXPECT_EQ(s.confusion[1][1], 1);
  EXPECT_DOUBLE_EQ(*s.accuracy, 1.0);
  EXPECT_TRUE(s.movers_seen_only_standing.empty());
}

TEST(ClassificationTest, AMoverLabelledStaticWhileWalkingIsWrong) {
  // The same walk, but the estimator keeps calling it static: judged at its last walking scan.
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  const auto M = ObjectLabel::kMoving;
  acc.AddScan(0, {Truth(1, 0, M, true, false)}, {Track(7, 0, M)});
  acc.AddScan(kScanUs, {Truth(1, 0, M, true, false)}, {Track(7, 0, S)});
  acc.AddScan(2 * kScanUs, {Truth(1, 0, M, true, true)}, {Track(7, 0, M)});  // not judged
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].final_label, S);
  EXPECT_FALSE(s.objects[0].correct);
  EXPECT_EQ(s.confusion[1][0], 1);
}

TEST(ClassificationTest, AMoverSeenOnlyStandingIsNotScoredButListed) {
  // Object 1 stands wherever it is visible (it walks only while occluded); its track still takes
  // part in the matching, so track 7 cannot go to the static object 2 beside it.
  ClassificationAccumulator acc(1.0);
  const auto S = ObjectLabel::kStatic;
  const auto M = ObjectLabel::kMoving;
  acc.AddScan(0, {Truth(1, 0, M, true, true), Truth(2, 0.5, S)}, {Track(7, 0, S)});
  acc.AddScan(kScanUs, {Truth(1, 3, M, false, false), Truth(2, 0.5, S)}, {});
  acc.AddScan(2 * kScanUs, {Truth(1, 6, M, true, true), Truth(2, 0.5, S)}, {Track(7, 6, S)});
  const ClassificationSummary s = acc.Summary();
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].id, 2);
  EXPECT_FALSE(s.objects[0].final_label.has_value());  // track 7 was the mover's
  EXPECT_EQ(s.movers_seen_only_standing, std::vector<int64_t>{1});
  EXPECT_DOUBLE_EQ(*s.accuracy, 0.0);
}

TEST(ClassificationTest, NothingVisibleLeavesAccuracyUndefined) {
  ClassificationAccumulator acc(1.0);
  acc.AddScan(0, {}, {Track(1, 0, ObjectLabel::kMoving)});
  const ClassificationSummary s = acc.Summary();
  EXPECT_TRUE(s.objects.empty());
  EXPECT_FALSE(s.accuracy.has_value());
}

TEST(ClassificationTest, RejectsBadInput) {
  ClassificationAccumulator acc(1.0);
  EXPECT_THROW(acc.AddScan(0, {Truth(1, 0, ObjectLabel::kUndecided)}, {}),
               std::invalid_argument);
  EXPECT_THROW(acc.AddScan(0, {}, {Track(1, 0, ObjectLabel::kMoving),
                                   Track(1, 3, ObjectLabel::kMoving)}),
               std::invalid_argument);
  EXPECT_THROW(acc.AddScan(0, {Truth(1, 0, ObjectLabel::kStatic, true, true)}, {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
