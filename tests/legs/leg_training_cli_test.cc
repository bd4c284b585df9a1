// The short version of leg_model_retraining_test.cc (label long): `slammtt-legs train`, the
// program scripts/train-leg-model.sh runs, trains on the committed fixture (20 labelled scans of
// positive_1_extracted, tests/data/leg_tracker) and a few simulated office scans in seconds and
// writes the same model source on every run. Needs no ../shared and no venv.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::RunProcess;
using testing::TempDir;

const char kFixture[] =
    SLAMMTT_SOURCE_DIR "/tests/data/leg_tracker/positive_1_extracted_first20.lcm";
// The fixture's 20 scans alone give too few non-legs to train on; 31 scans of the world's
// office give both classes.
const char kOffice[] = SLAMMTT_SOURCE_DIR "/config/scenarios/office.yaml";

std::string TrainOnTheFixture(const TempDir& dir, const std::string& name) {
  const std::vector<std::string> argv = {std::string(SLAMMTT_BIN_DIR) + "/slammtt-legs",
                                         "train",
                                         "--labelled",
                                         std::string("fixture=") + kFixture,
                                         "--simulated",
                                         std::string("office=") + kOffice,
                                         "--simulated-seeds",
                                         "101",
                                         "--simulated-every",
                                         "40",
                                         "--strides",
                                         "1,2",
                                         "--threshold",
                                         "0.30",
                                         "-q",
                                         "-o",
                                         dir.File(name)};
  const testing::ProcessResult r = RunProcess(argv, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return testing::ReadWholeFile(dir.File(name));
}

TEST(LegTrainingCliTest, TheFixtureTrainsTheSameModelSourceTwice) {
  TempDir dir("slammtt-leg-training");
  const std::string first = TrainOnTheFixture(dir, "a.cc");
  const std::string second = TrainOnTheFixture(dir, "b.cc");
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, second);
  EXPECT_NE(first.find("const LegModel& TrainedLegModel()"), std::string::npos);
}

TEST(LegTrainingCliTest, AnUnknownRecordingIsAOneLineError) {
  TempDir dir("slammtt-leg-training");
  const testing::ProcessResult r =
      RunProcess({std::string(SLAMMTT_BIN_DIR) + "/slammtt-legs", "train", "--labelled",
                  "fixture=" + dir.File("absent.lcm"), "-o", dir.File("m.cc")},
                 dir.path());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("absent.lcm"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.File("m.cc")));
}

}  // namespace
}  // namespace slammtt
