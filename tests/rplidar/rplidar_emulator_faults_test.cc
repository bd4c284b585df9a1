// slammtt-rplidar-emulator's faults: kinds, default arguments and their schedule.
#include "drivers/rplidar/rplidar_emulator_faults.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/common/fault_schedule.h"

namespace slammtt {
namespace rplidar {
namespace {

using Kind = RplidarEmulatorFault::Kind;

TEST(RplidarEmulatorFaultsTest, EveryKindWithItsDefaultArgument) {
  const std::vector<std::tuple<std::string, Kind, double>> cases = {
      {"garbage@1", Kind::kGarbage, 100.0},      {"bad-checksum@1", Kind::kBadChecksum, 1.0},
      {"drop@1", Kind::kDrop, 1.0},              {"silence@1", Kind::kSilence, 3.0},
      {"mute@1", Kind::kMute, 3.0},              {"disconnect@1", Kind::kDisconnect, 3.0}};
  for (const auto& [text, kind, argument] : cases) {
    const RplidarEmulatorFault fault = ParseRplidarEmulatorFault(text);
    EXPECT_EQ(fault.kind, kind) << text;
    EXPECT_EQ(fault.name, text.substr(0, text.find('@')));
    EXPECT_DOUBLE_EQ(fault.at_s, 1.0);
    EXPECT_DOUBLE_EQ(fault.argument, argument) << text;
  }
  EXPECT_EQ(RplidarEmulatorFaultNames().size(), cases.size());
}

TEST(RplidarEmulatorFaultsTest, AGivenArgumentWins) {
  const RplidarEmulatorFault fault = ParseRplidarEmulatorFault("disconnect@10.5:2");
  EXPECT_EQ(fault.kind, Kind::kDisconnect);
  EXPECT_DOUBLE_EQ(fault.at_s, 10.5);
  EXPECT_DOUBLE_EQ(fault.argument, 2.0);
  EXPECT_DOUBLE_EQ(ParseRplidarEmulatorFault("garbage@0:300").argument, 300.0);
}

TEST(RplidarEmulatorFaultsTest, MistakesAreOneLineErrors) {
  for (const std::string text : {"boom@1", "garbage", "garbage@x", "garbage@1:x", "mute@1:-1"}) {
    try {
      ParseRplidarEmulatorFault(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string error = e.what();
      EXPECT_NE(error.find("'" + text + "'"), std::string::npos) << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
  }
}

TEST(RplidarEmulatorFaultsTest, TheScheduleFiresTheFaultsAtTheirTimes) {
  std::vector<RplidarEmulatorFault> faults = {ParseRplidarEmulatorFault("silence@4:1"),
                                              ParseRplidarEmulatorFault("garbage@1"),
                                              ParseRplidarEmulatorFault("drop@1:5")};
  FaultSchedule schedule(FaultTimes(faults));
  EXPECT_TRUE(schedule.TakeDue(0.98).empty());
  const std::vector<size_t> at_1 = schedule.TakeDue(1.0);
  ASSERT_EQ(at_1, (std::vector<size_t>{1, 2}));
  EXPECT_EQ(faults[at_1[0]].kind, Kind::kGarbage);
  EXPECT_EQ(faults[at_1[1]].kind, Kind::kDrop);
  EXPECT_TRUE(schedule.TakeDue(3.9).empty());
  EXPECT_EQ(schedule.TakeDue(4.02), (std::vector<size_t>{0}));
  EXPECT_EQ(schedule.pending(), 0u);
}

}  // namespace
}  // namespace rplidar
}  // namespace slammtt
