#include "drivers/common/fault_schedule.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace slammtt {
namespace {

const std::vector<std::string> kKinds = {"garbage", "disconnect"};

std::string ErrorOf(const std::string& text) {
  try {
    ParseScheduledFault(text, kKinds);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FaultScheduleTest, ParsesKindTimeAndArgument) {
  const ScheduledFault with = ParseScheduledFault("disconnect@10.5:2", kKinds);
  EXPECT_EQ(with.kind, "disconnect");
  EXPECT_DOUBLE_EQ(with.at_s, 10.5);
  EXPECT_EQ(with.argument, "2");
  const ScheduledFault without = ParseScheduledFault("garbage@0", kKinds);
  EXPECT_EQ(without.kind, "garbage");
  EXPECT_DOUBLE_EQ(without.at_s, 0.0);
  EXPECT_EQ(without.argument, "");
  // The argument's form is the emulator's business (the P3-DX bumper fault takes "3,0").
  EXPECT_EQ(ParseScheduledFault("garbage@1:3,0", kKinds).argument, "3,0");
}

TEST(FaultScheduleTest, MistakesAreOneLineErrorsQuotingTheFault) {
  for (const std::string text :
       {"garbage", "boom@1", "garbage@", "garbage@x", "garbage@-1", "garbage@nan", "garbage@1e7",
        "garbage@1s"}) {
    const std::string error = ErrorOf(text);
    EXPECT_NE(error.find("'" + text + "'"), std::string::npos) << text << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  EXPECT_NE(ErrorOf("boom@1").find("garbage, disconnect"), std::string::npos);
}

TEST(FaultScheduleTest, NumericArgumentsAreBoundedAndDefaulted) {
  EXPECT_DOUBLE_EQ(FaultNumber("", 64.0, "garbage@1"), 64.0);
  EXPECT_DOUBLE_EQ(FaultNumber("300", 64.0, "garbage@1:300"), 300.0);
  EXPECT_DOUBLE_EQ(FaultNumber("1.5", 0.0, "silence@1:1.5"), 1.5);
  for (const std::string bad : {"-1", "x", "1x", "inf", "nan", "1e300", "1000001"}) {
    EXPECT_THROW(FaultNumber(bad, 1.0, "garbage@1:" + bad), std::invalid_argument) << bad;
  }
}

TEST(FaultScheduleTest, EachFaultFiresOnceWhenItsTimeHasCome) {
  FaultSchedule schedule({2.0, 0.0, 5.0});
  EXPECT_EQ(schedule.pending(), 3u);
  EXPECT_EQ(schedule.TakeDue(0.0), (std::vector<size_t>{1}));  // at 0 s: due at the start
  EXPECT_TRUE(schedule.TakeDue(0.5).empty());
  EXPECT_TRUE(schedule.TakeDue(1.999).empty());
  EXPECT_EQ(schedule.TakeDue(2.0), (std::vector<size_t>{0}));  // the time itself is due
  EXPECT_TRUE(schedule.TakeDue(2.1).empty()) << "fired once only";
  EXPECT_EQ(schedule.pending(), 1u);
  EXPECT_EQ(schedule.TakeDue(100.0), (std::vector<size_t>{2}));
  EXPECT_EQ(schedule.pending(), 0u);
  EXPECT_TRUE(schedule.TakeDue(1000.0).empty());
}

TEST(FaultScheduleTest, FaultsDueTogetherFireInTheOrderGiven) {
  // A late look at the clock (the emulator slept past two times) fires both, in command-line
  // order, not by time.
  FaultSchedule schedule({3.0, 1.0, 2.0});
  EXPECT_EQ(schedule.TakeDue(2.5), (std::vector<size_t>{1, 2}));
  EXPECT_EQ(schedule.TakeDue(3.0), (std::vector<size_t>{0}));
}

TEST(FaultScheduleTest, AnEmptyScheduleHasNothingDue) {
  FaultSchedule schedule({});
  EXPECT_EQ(schedule.pending(), 0u);
  EXPECT_TRUE(schedule.TakeDue(1e6).empty());
}

}  // namespace
}  // namespace slammtt
