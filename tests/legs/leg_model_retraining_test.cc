// The committed model (perception/leg_model.cc) is what scripts/train-leg-model.sh writes from
// the leg_tracker recordings, byte for byte. 3-4 min of CPU (15 min and more on a loaded
// machine), so label `long`: it runs with SLAMMTT_LONG_TESTS=1 scripts/run-tests.sh. The default
// suite runs the short version, leg_training_cli_test.cc (the same program on the committed
// fixture). Skipped, with the reason, without ../shared or the Python venv.
#include <gtest/gtest.h>

#include <string>

#include "tests/legs/shared_recordings.h"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::LegRecordingsUnavailable;
using testing::RunProcess;
using testing::SharedReal;
using testing::TempDir;

TEST(LegModelTest, RetrainingWritesTheCommittedModel) {
  const std::string why = LegRecordingsUnavailable();
  if (!why.empty()) GTEST_SKIP() << why;
  TempDir dir("slammtt-leg-model");
  const testing::ProcessResult r = RunProcess(
      {std::string(SLAMMTT_SOURCE_DIR) + "/scripts/train-leg-model.sh", "--shared",
       SharedReal() + "/../..", "--out", dir.File("leg_model.cc"), "--work", dir.path()},
      dir.path(), 2400000);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(testing::ReadWholeFile(dir.File("leg_model.cc")),
            testing::ReadWholeFile(std::string(SLAMMTT_SOURCE_DIR) + "/perception/leg_model.cc"))
      << "perception/leg_model.cc is not what scripts/train-leg-model.sh writes";
}

}  // namespace
}  // namespace slammtt
