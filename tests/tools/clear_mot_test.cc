#include "tools/metrics/clear_mot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace slammtt {
namespace {

constexpr double kThreshold = 1.0;

IdentifiedPoint At(int64_t id, double x, double y) {
  return IdentifiedPoint{id, Eigen::Vector2d(x, y)};
}

TEST(ClearMotTest, NothingAtAllLeavesMotaAndMotpUndefined) {
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({}, {});
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_frames, 1);
  EXPECT_EQ(s.num_truth, 0);
  EXPECT_FALSE(s.mota.has_value());
  EXPECT_FALSE(s.motp_m.has_value());
}

TEST(ClearMotTest, AllMissedGivesMotaZero) {
  ClearMotAccumulator acc(kThreshold);
  for (int f = 0; f < 3; ++f) acc.AddFrame({At(1, 0, 0), At(2, 5, 0)}, {});
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_truth, 6);
  EXPECT_EQ(s.num_misses, 6);
  EXPECT_EQ(s.num_false_positives, 0);
  ASSERT_TRUE(s.mota.has_value());
  EXPECT_DOUBLE_EQ(*s.mota, 0.0);
  EXPECT_FALSE(s.motp_m.has_value());
}

TEST(ClearMotTest, AllFalseCountsFalsePositives) {
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({}, {At(7, 0, 0), At(8, 2, 0)});
  acc.AddFrame({At(1, 10, 0)}, {At(7, 0, 0), At(8, 2, 0)});
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_false_positives, 4);
  EXPECT_EQ(s.num_misses, 1);
  ASSERT_TRUE(s.mota.has_value());
  EXPECT_DOUBLE_EQ(*s.mota, 1.0 - 5.0 / 1.0);  // MOTA is unbounded below
}

TEST(ClearMotTest, PerfectTrackingHandComputed) {
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0), At(2, 5, 0)}, {At(10, 0.3, 0.4), At(20, 5, 0.1)});
  acc.AddFrame({At(1, 1, 0), At(2, 5, 1)}, {At(10, 1, 0.2), At(20, 5, 1.3)});
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_matches, 4);
  EXPECT_EQ(s.num_id_switches, 0);
  EXPECT_DOUBLE_EQ(*s.mota, 1.0);
  EXPECT_NEAR(*s.motp_m, (0.5 + 0.1 + 0.2 + 0.3) / 4.0, 1e-12);
}

TEST(ClearMotTest, ThresholdIsInclusive) {
  ClearMotAccumulator acc(kThreshold);
  const ClearMotFrame at = acc.AddFrame({At(1, 0, 0)}, {At(9, 1.0, 0)});
  EXPECT_EQ(at.num_matches, 1);
  ClearMotAccumulator acc2(kThreshold);
  const ClearMotFrame beyond = acc2.AddFrame({At(1, 0, 0)}, {At(9, 1.01, 0)});
  EXPECT_EQ(beyond.num_matches, 0);
  EXPECT_EQ(beyond.num_misses, 1);
  EXPECT_EQ(beyond.num_false_positives, 1);
}

TEST(ClearMotTest, TrackReplacedByANewIdentityIsOneSwitch) {
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0)}, {At(10, 0, 0)});
  acc.AddFrame({At(1, 1, 0)}, {At(10, 1, 0)});
  const ClearMotFrame f = acc.AddFrame({At(1, 2, 0)}, {At(11, 2, 0)});
  EXPECT_EQ(f.num_id_switches, 1);
  acc.AddFrame({At(1, 3, 0)}, {At(11, 3, 0)});  // the new identity then holds: no more switches
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_id_switches, 1);
  EXPECT_DOUBLE_EQ(*s.mota, 1.0 - 1.0 / 4.0);
}

TEST(ClearMotTest, TrackHoppingToAnUntrackedObjectIsOneSwitch) {
  // Object 1 is tracked by 10; object 2 (far away) is untracked. Then 10 jumps to object 2 and a
  // new track 11 picks up object 1: object 1 switched (10 -> 11), object 2 had no identity yet.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0), At(2, 5, 0)}, {At(10, 0, 0)});
  const ClearMotFrame f = acc.AddFrame({At(1, 0, 0), At(2, 5, 0)}, {At(10, 5, 0), At(11, 0, 0)});
  EXPECT_EQ(f.num_id_switches, 1);
  EXPECT_EQ(f.num_matches, 2);
}

TEST(ClearMotTest, TwoTracksExchangingObjectsAreTwoSwitches) {
  // CLEAR-MOT counts switches per true object: when two tracks exchange their objects, both
  // objects change identity.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 0, 0), At(20, 3, 0)});
  const ClearMotFrame f = acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 3, 0), At(20, 0, 0)});
  EXPECT_EQ(f.num_id_switches, 2);
}

TEST(ClearMotTest, KeepsTheLastCorrespondenceWhileWithinThreshold) {
  // Hungarian alone would give object 1 the nearer track 11; the carried-over correspondence
  // keeps track 10 (still within 1 m), so there is no switch and 11 is a false positive.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0)}, {At(10, 0, 0)});
  const ClearMotFrame f = acc.AddFrame({At(1, 0, 0)}, {At(10, 0.8, 0), At(11, 0.1, 0)});
  EXPECT_EQ(f.num_id_switches, 0);
  ASSERT_EQ(f.matches.size(), 1u);
  EXPECT_EQ(f.matches[0], (std::pair<int64_t, int64_t>(1, 10)));
  EXPECT_EQ(f.num_false_positives, 1);
}

TEST(ClearMotTest, CorrespondenceSurvivesAFrameOutOfView) {
  // The object is invisible (not in the truth set) for one scan and comes back to its track.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0)}, {At(10, 0, 0)});
  acc.AddFrame({}, {At(10, 0.5, 0)}, DontCare{{}, {Eigen::Vector2d(0.5, 0)}});
  const ClearMotFrame f = acc.AddFrame({At(1, 1, 0)}, {At(10, 1, 0)});
  EXPECT_EQ(f.num_id_switches, 0);
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_fragmentations, 0);  // absent frames do not interrupt
  EXPECT_EQ(s.num_false_positives, 0);  // the coasting track was a don't-care
  EXPECT_EQ(s.num_dont_care, 1);
}

TEST(ClearMotTest, DontCareExcusesOnlyNearbyUnmatchedTracks) {
  ClearMotAccumulator acc(kThreshold);
  const ClearMotFrame f = acc.AddFrame({At(1, 0, 0)}, {At(10, 0, 0), At(11, 5.5, 0),
                                                      At(12, 9, 0)},
                                       DontCare{{}, {Eigen::Vector2d(5, 0)}});
  EXPECT_EQ(f.num_matches, 1);
  EXPECT_EQ(f.num_dont_care, 1);
  EXPECT_EQ(f.dont_care_hypotheses, std::vector<int64_t>{11});
  EXPECT_EQ(f.num_false_positives, 1);
}

TEST(ClearMotTest, CountsFragmentations) {
  ClearMotAccumulator acc(kThreshold);
  const std::vector<IdentifiedPoint> truth = {At(1, 0, 0)};
  const std::vector<IdentifiedPoint> tracked = {At(10, 0, 0)};
  acc.AddFrame(truth, {});       // not yet tracked: no fragmentation
  acc.AddFrame(truth, tracked);
  acc.AddFrame(truth, {});       // lost
  acc.AddFrame(truth, {});
  EXPECT_EQ(acc.AddFrame(truth, tracked).num_fragmentations, 1);  // back
  acc.AddFrame(truth, {});
  EXPECT_EQ(acc.AddFrame(truth, tracked).num_fragmentations, 1);
  acc.AddFrame(truth, {});      // lost at the end: not a fragmentation (never came back)
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_fragmentations, 2);
  EXPECT_EQ(s.num_id_switches, 0);
  EXPECT_EQ(s.num_misses, 5);
}

TEST(ClearMotTest, AMoverStandingStillIsDontCareAndKeepsItsTrack) {
  // Object 1 walks (tracked by 10), stands for three frames, then walks again. While it stands
  // it is a don't-care object: its track 10 is excused (neither a match nor a false positive),
  // a second track 11 beside it is not (one excuse per object), and a frame where the track is
  // gone is not a miss. Back in the truth set, it is still matched to 10: no switch, and no
  // fragmentation, although it was untracked in a standing frame.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0)}, {At(10, 0.1, 0)});
  const ClearMotFrame standing =
      acc.AddFrame({}, {At(10, 1.2, 0), At(11, 1.5, 0)}, DontCare{{At(1, 1, 0)}, {}});
  EXPECT_EQ(standing.num_truth, 0);
  EXPECT_EQ(standing.num_dont_care, 1);
  EXPECT_EQ(standing.num_dont_care_objects, 1);
  EXPECT_EQ(standing.num_dont_care_positions, 0);
  EXPECT_EQ(standing.dont_care_hypotheses, std::vector<int64_t>{10});  // the nearer one
  EXPECT_EQ(standing.num_false_positives, 1);
  const ClearMotFrame untracked = acc.AddFrame({}, {}, DontCare{{At(1, 1, 0)}, {}});
  EXPECT_EQ(untracked.num_misses, 0);
  acc.AddFrame({}, {At(10, 1, 0.5)}, DontCare{{At(1, 1, 0)}, {}});
  const ClearMotFrame walking = acc.AddFrame({At(1, 2, 0)}, {At(10, 2, 0.3), At(12, 2, 0)});
  EXPECT_EQ(walking.num_id_switches, 0);
  EXPECT_EQ(walking.num_fragmentations, 0);
  ASSERT_EQ(walking.matches.size(), 1u);
  EXPECT_EQ(walking.matches[0], (std::pair<int64_t, int64_t>(1, 10)));  // kept, not the nearer
  const ClearMotSummary s = acc.Summary();
  EXPECT_EQ(s.num_truth, 2);
  EXPECT_EQ(s.num_matches, 2);
  EXPECT_EQ(s.num_false_positives, 2);  // 11 beside the standing object, 12 at the end
  EXPECT_EQ(s.num_dont_care, 2);
  EXPECT_EQ(s.num_dont_care_objects, 2);
  EXPECT_DOUBLE_EQ(*s.mota, 1.0 - 2.0 / 2.0);
}

TEST(ClearMotTest, AStandingObjectExcusesOnlyWhatTheTruthSetLeaves) {
  // Object 2 walks 0.5 m from the standing object 1; the only track there goes to the truth set
  // first, so nothing is excused. A track 3 m away is excused by neither.
  ClearMotAccumulator acc(kThreshold);
  const ClearMotFrame f =
      acc.AddFrame({At(2, 0.5, 0)}, {At(10, 0.2, 0), At(11, 3, 0)}, DontCare{{At(1, 0, 0)}, {}});
  EXPECT_EQ(f.num_matches, 1);
  EXPECT_EQ(f.num_dont_care, 0);
  EXPECT_EQ(f.num_false_positives, 1);
}

TEST(ClearMotTest, ResumingOnANewTrackIsOneListedSwitch) {
  // The estimator turned the standing person into a landmark and made a new track when it
  // walked on: the identity changed (10 -> 20) and the switch is listed.
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0)}, {At(10, 0, 0)});
  acc.AddFrame({}, {}, DontCare{{At(1, 0, 0)}, {}});
  const ClearMotFrame f = acc.AddFrame({At(1, 0.5, 0)}, {At(20, 0.5, 0)});
  EXPECT_EQ(f.num_id_switches, 1);
  ASSERT_EQ(f.id_switches.size(), 1u);
  EXPECT_EQ(f.id_switches[0].truth_id, 1);
  EXPECT_EQ(f.id_switches[0].previous_hypothesis_id, 10);
  EXPECT_EQ(f.id_switches[0].new_hypothesis_id, 20);
}

TEST(ClearMotTest, ListsEverySwitchAndFragmentation) {
  // Frames 0-1: 1 by 10, 2 by 20. Frame 2: they exchange (two switches). Frames 3-4: object 1
  // untracked. Frame 5: 1 back on 20 (a fragmentation that began at frame 3, no switch).
  ClearMotAccumulator acc(kThreshold);
  acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 0, 0), At(20, 3, 0)});
  acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 0, 0), At(20, 3, 0)});
  const ClearMotFrame exchange =
      acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 3, 0), At(20, 0, 0)});
  ASSERT_EQ(exchange.id_switches.size(), 2u);
  EXPECT_EQ(exchange.id_switches[0].truth_id, 1);
  EXPECT_EQ(exchange.id_switches[0].previous_hypothesis_id, 10);
  EXPECT_EQ(exchange.id_switches[0].new_hypothesis_id, 20);
  EXPECT_EQ(exchange.id_switches[1].truth_id, 2);
  EXPECT_EQ(exchange.id_switches[1].previous_hypothesis_id, 20);
  EXPECT_EQ(exchange.id_switches[1].new_hypothesis_id, 10);
  acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 3, 0)});
  acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 3, 0)});
  const ClearMotFrame back =
      acc.AddFrame({At(1, 0, 0), At(2, 3, 0)}, {At(10, 3, 0), At(20, 0, 0)});
  EXPECT_TRUE(back.id_switches.empty());
  ASSERT_EQ(back.fragmentations.size(), 1u);
  EXPECT_EQ(back.fragmentations[0].truth_id, 1);
  EXPECT_EQ(back.fragmentations[0].previous_hypothesis_id, 20);
  EXPECT_EQ(back.fragmentations[0].new_hypothesis_id, 20);
  EXPECT_EQ(back.fragmentations[0].untracked_since_frame, 3);
  EXPECT_EQ(acc.Summary().num_id_switches, 2);
  EXPECT_EQ(acc.Summary().num_fragmentations, 1);
}

TEST(ClearMotTest, RejectsDuplicateIdsAndNonFinitePositions) {
  ClearMotAccumulator acc(kThreshold);
  EXPECT_THROW(acc.AddFrame({At(1, 0, 0), At(1, 1, 0)}, {}), std::invalid_argument);
  EXPECT_THROW(acc.AddFrame({}, {At(3, std::numeric_limits<double>::infinity(), 0)}),
               std::invalid_argument);
  EXPECT_THROW(ClearMotAccumulator(0.0), std::invalid_argument);
  // A don't-care object that is also in the truth set, or repeated, is a caller's bug.
  EXPECT_THROW(acc.AddFrame({At(1, 0, 0)}, {}, DontCare{{At(1, 0, 0)}, {}}),
               std::invalid_argument);
  EXPECT_THROW(acc.AddFrame({}, {}, DontCare{{At(2, 0, 0), At(2, 1, 0)}, {}}),
               std::invalid_argument);
  EXPECT_THROW(
      acc.AddFrame({}, {}, DontCare{{}, {Eigen::Vector2d(std::nan(""), 0.0)}}),
      std::invalid_argument);
}

}  // namespace
}  // namespace slammtt
