// The leg classifier on the leg_tracker recordings it never saw in training (positive_4, the
// second half of negative_2, the demo bag), with floors at the figures measured on the commit
// that trained the model (docs/perception.md, "Learned leg classifier"). The recordings are read
// from ../shared (or $SLAMMTT_SHARED_DIR) through slammtt-import, which needs the Python venv
// (scripts/python-env.sh); without either every test here is skipped with the reason. The
// model's retraining from the recordings is leg_model_retraining_test.cc (label long).
#include <gtest/gtest.h>

#include <string>

#include "tests/legs/shared_recordings.h"
#include "tests/support/child_process.h"
#include "tools/legs/leg_training.h"
#include "tools/legs/recording_log.h"

namespace slammtt {
namespace {

// Measured on the commit that trained perception/leg_model.cc (docs/perception.md).
// With SegmenterOptions{} (this test): positive_4 recall 0.9108, precision in the arc 1.0000,
// labelled legs that are a leg of a person feature 0.8024 (0.8145 before surface pieces made no
// person and max_leg_separation_m became 0.7); negative_2's second half 2.940 false people per
// scan (3.188 before; 2.899 since leg-like clusters within 0.025 m of a line of the scan are
// pieces of it; 2.839 with person_single_leg_surface_clearance_m 0.2 and
// person_separate_dropout_pieces, both off by default, which take positive_4's labelled legs in
// a person to 0.8000); the demo: 1-3 people in 0.9502 of the scans (0.951 before; 0.9510 now).
// (slammtt-legs evaluate reads the options through ReadSegmenterOptions, whose degree
// conversions differ in the last bits; the figures agree there to the digits given.)
constexpr double kP4RecallFloor = 0.91;
constexpr double kP4PrecisionFloor = 0.99;
constexpr double kP4LegsInPeopleFloor = 0.79;
constexpr double kNegative2PeoplePerScanCeiling = 2.91;
constexpr double kDemoOneToThreeFloor = 0.95;

using testing::LegRecordingsUnavailable;
using testing::RunProcess;
using testing::SharedReal;
using testing::TempDir;

class RealLegsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = LegRecordingsUnavailable();
    if (!why.empty()) GTEST_SKIP() << why;
  }
  Recording Import(const std::string& bag, const std::string& name,
                   const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {std::string(SLAMMTT_BIN_DIR) + "/slammtt-import",
                                     SharedReal() + "/" + bag, "-o", dir_.File(name + ".lcm"),
                                     "--no-odometry", "-q"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const testing::ProcessResult r = RunProcess(argv, dir_.path());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return ReadRecording(name, dir_.File(name + ".lcm"));
  }
  TempDir dir_{"slammtt-legs"};
};

// positive_4_extracted: labels within (-15, 10) degrees and 5 m (leg_dataset.h).
TEST_F(RealLegsTest, HeldOutPositive4LegRecallAndPrecision) {
  const Recording p4 = Import("leg_tracker_training/positive_4_extracted.bag", "p4");
  ASSERT_EQ(p4.scans.size(), 295u);
  const SegmenterOptions options;
  const LegDetectionScore s = EvaluateRecording(p4, options, 1, LabelArc{-15.0, 10.0, 5.0});
  std::cout << "positive_4: labels " << s.labels << ", recall " << s.recall() << ", precision "
            << s.precision() << ", labelled legs in a person " << s.person_leg_recall() << "\n";
  EXPECT_EQ(s.labels, 415);
  EXPECT_GE(s.recall(), kP4RecallFloor);
  EXPECT_GE(s.precision(), kP4PrecisionFloor);
  // What reaches the tracker: a label stands under a person feature.
  EXPECT_GE(s.person_leg_recall(), kP4LegsInPeopleFloor);
}

// negative_2, second half of /left_scan (the first half of all three lasers is training data).
TEST_F(RealLegsTest, HeldOutNegative2FalsePeople) {
  const Recording n2 = PartOf(Import("leg_tracker_training/negative_2.bag", "n2"), 0.5, 1.0);
  const LegDetectionScore s = EvaluateRecording(n2, SegmenterOptions{}, 1, LabelArc{});
  std::cout << "negative_2 second half: " << s.scans << " scans, " << s.people
            << " false people, " << s.people_per_minute() << " per minute\n";
  EXPECT_LE(s.people_per_scan(), kNegative2PeoplePerScanCeiling);
}

// leg_tracker_demo: 1-3 people walk in front of a standing scanner.
TEST_F(RealLegsTest, DemoPeoplePerScan) {
  const Recording demo = Import("leg_tracker_demo/demo_stationary_simple_environment.bag", "demo");
  const LegDetectionScore s = EvaluateRecording(demo, SegmenterOptions{}, 1, LabelArc{});
  const auto& h = s.people_per_scan_histogram;
  ASSERT_EQ(h.size(), 6u);
  const double one_to_three = static_cast<double>(h[1] + h[2] + h[3]) / static_cast<double>(s.scans);
  std::cout << "demo: " << s.people_per_scan() << " people per scan; 1-3 people in "
            << one_to_three << " of the scans\n";
  EXPECT_GE(one_to_three, kDemoOneToThreeFloor);
}

}  // namespace
}  // namespace slammtt
