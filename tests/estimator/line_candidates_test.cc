// Step 1b.6, candidate lines (estimator/line_candidates.h): which sighting continues a
// candidate, when a candidate is confirmed, when it is dropped.
#include "estimator/line_candidates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "estimator/line_landmarks.h"

namespace slammtt {
namespace {

constexpr int64_t kSecond = 1000000;

// A sighting of the line (rho_m, alpha_rad) of the map frame over [from_m, to_m] at `utime`.
LineCandidate Seen(double rho_m, double alpha_rad, double from_m, double to_m, int64_t utime) {
  LineCandidate c;
  c.line = Eigen::Vector2d(rho_m, alpha_rad);
  c.extent_from_m = from_m;
  c.extent_to_m = to_m;
  c.scans = 1;
  c.first_seen_utime = utime;
  c.last_seen_utime = utime;
  return c;
}

TEST(LineCandidatesTest, TheSameLineContinuesWithinTheMatchDistances) {
  const LineLandmarkOptions options;  // 0.1 m, 2 degrees, extent gap 1 m
  const LineCandidate wall = Seen(3.0, 0.0, -1.0, 1.0, kSecond);
  EXPECT_TRUE(ContinuesLineCandidate(Seen(3.05, 0.01, -1.0, 1.0, 0), wall, options));
  EXPECT_FALSE(ContinuesLineCandidate(Seen(3.15, 0.0, -1.0, 1.0, 0), wall, options));
  EXPECT_FALSE(ContinuesLineCandidate(Seen(3.0, 0.05, -1.0, 1.0, 0), wall, options));
  // Extents 0.9 m apart join (a door); 1.1 m apart stay apart (another wall on the line).
  EXPECT_TRUE(ContinuesLineCandidate(Seen(3.0, 0.0, 1.9, 3.0, 0), wall, options));
  EXPECT_FALSE(ContinuesLineCandidate(Seen(3.0, 0.0, 2.1, 3.0, 0), wall, options));
  EXPECT_FALSE(ContinuesLineCandidate(Seen(3.0, 0.0, -4.0, -2.1, 0), wall, options));
}

TEST(LineCandidatesTest, TheSameLineWrittenWithTheOtherSignContinues) {
  const LineLandmarkOptions options;
  const LineCandidate wall = Seen(3.0, 0.0, 0.0, 2.0, kSecond);
  // (-rho, alpha + pi) is the same line, with its coordinate along the line running the other
  // way: [-3, -1.5] written so is [1.5, 3] in the candidate's coordinates (overlapping [0, 2]),
  // and [1.5, 3] is [-3, -1.5] (more than the 1 m gap away).
  EXPECT_TRUE(ContinuesLineCandidate(Seen(-3.0, M_PI, -3.0, -1.5, 0), wall, options));
  EXPECT_TRUE(ContinuesLineCandidate(Seen(-3.02, M_PI - 0.01, -3.0, -1.5, 0), wall, options));
  EXPECT_FALSE(ContinuesLineCandidate(Seen(-3.0, M_PI, 1.5, 3.0, 0), wall, options));
  // (3, pi) is the line x = -3, on the other side of the robot.
  EXPECT_FALSE(ContinuesLineCandidate(Seen(3.0, M_PI, 0.0, 2.0, 0), wall, options));
}

TEST(LineCandidatesTest, ACandidateIsConfirmedInItsConfirmScansThScan) {
  LineLandmarkOptions options;
  options.confirm_scans = 3;
  std::vector<LineCandidate> candidates;
  EXPECT_FALSE(ConfirmLineCandidate(Seen(3.0, 0.0, -1.0, 1.0, 1 * kSecond), options,
                                    &candidates));
  ASSERT_EQ(candidates.size(), 1u);
  // A second sighting in the same scan (two pieces of the wall) does not count as a scan.
  EXPECT_FALSE(ConfirmLineCandidate(Seen(3.0, 0.0, 1.5, 2.0, 1 * kSecond), options,
                                    &candidates));
  EXPECT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].scans, 1);
  // The next scan continues the first candidate, which takes the latest line and extent.
  EXPECT_FALSE(ConfirmLineCandidate(Seen(3.01, 0.0, -0.5, 1.2, 2 * kSecond), options,
                                    &candidates));
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].scans, 2);
  EXPECT_EQ(candidates[0].first_seen_utime, 1 * kSecond);
  EXPECT_EQ(candidates[0].last_seen_utime, 2 * kSecond);
  EXPECT_DOUBLE_EQ(candidates[0].line(0), 3.01);
  EXPECT_DOUBLE_EQ(candidates[0].extent_from_m, -0.5);
  EXPECT_DOUBLE_EQ(candidates[0].extent_to_m, 1.2);
  // The third scan confirms it: it leaves the list, the other candidate stays.
  EXPECT_TRUE(ConfirmLineCandidate(Seen(3.0, 0.0, -1.0, 1.0, 3 * kSecond), options,
                                   &candidates));
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_DOUBLE_EQ(candidates[0].extent_from_m, 1.5);
}

TEST(LineCandidatesTest, CandidatesUnseenForLongerThanTheTimeoutAreDropped) {
  LineLandmarkOptions options;
  options.candidate_timeout_s = 0.5;
  std::vector<LineCandidate> candidates = {Seen(3.0, 0.0, -1.0, 1.0, 1 * kSecond),
                                           Seen(2.0, 1.0, -1.0, 1.0, kSecond + kSecond / 5)};
  DropStaleLineCandidates(kSecond + 4 * kSecond / 10, options, &candidates);  // 0.4 s, 0.2 s
  EXPECT_EQ(candidates.size(), 2u);
  DropStaleLineCandidates(kSecond + 6 * kSecond / 10, options, &candidates);  // 0.6 s, 0.4 s
  ASSERT_EQ(candidates.size(), 1u);
  EXPECT_DOUBLE_EQ(candidates[0].line(0), 2.0);
}

}  // namespace
}  // namespace slammtt
