// slammtt-teleop's pure parts: the velocity profile file and the terminal's keys.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/teleop/teleop_keys.h"
#include "drivers/teleop/velocity_profile.h"

namespace slammtt {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseVelocityProfile(text, "drive.txt");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(VelocityProfileTest, ParsesStepsSkippingCommentsAndBlankLines) {
  const std::vector<VelocityProfileStep> steps = ParseVelocityProfile(
      "# out of the corridor\n"
      "2.5 0.3 0   # straight\n"
      "\n"
      "   \t\n"
      "1 0.2 -0.4\n"
      "0.5\t-0.1\t1e-1\n",
      "drive.txt");
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_DOUBLE_EQ(steps[0].duration_s, 2.5);
  EXPECT_DOUBLE_EQ(steps[0].linear_mps, 0.3);
  EXPECT_DOUBLE_EQ(steps[0].angular_radps, 0.0);
  EXPECT_EQ(steps[0].line, 2);
  EXPECT_DOUBLE_EQ(steps[1].angular_radps, -0.4);
  EXPECT_EQ(steps[1].line, 5);
  EXPECT_DOUBLE_EQ(steps[2].linear_mps, -0.1);
  EXPECT_DOUBLE_EQ(steps[2].angular_radps, 0.1);
  EXPECT_EQ(steps[2].line, 6);
  EXPECT_DOUBLE_EQ(ProfileDurationS(steps), 4.0);
}

TEST(VelocityProfileTest, ABadLineIsOneLineNamingFileAndLine) {
  EXPECT_EQ(ErrorOf("1 0.3 0\n2 0.3\n"),
            "drive.txt:2: expected 'duration_s linear_mps angular_radps', got 2 fields");
  EXPECT_EQ(ErrorOf("# c\n1 fast 0\n"), "drive.txt:2: 'fast' is not a finite number");
  EXPECT_EQ(ErrorOf("1 nan 0\n"), "drive.txt:1: 'nan' is not a finite number");
  EXPECT_EQ(ErrorOf("0 0.1 0\n"), "drive.txt:1: duration_s must be in (0, 3600], got 0");
  EXPECT_EQ(ErrorOf("-1 0.1 0\n"), "drive.txt:1: duration_s must be in (0, 3600], got -1");
  EXPECT_EQ(ErrorOf("1 6 0\n"), "drive.txt:1: |linear_mps| must be at most 5, got 6");
  EXPECT_EQ(ErrorOf("1 0 -11\n"), "drive.txt:1: |angular_radps| must be at most 10, got -11");
  EXPECT_EQ(ErrorOf("1 0.1 0 7\n"),
            "drive.txt:1: expected 'duration_s linear_mps angular_radps', got 4 fields");
  EXPECT_EQ(ErrorOf("# only comments\n\n"), "drive.txt: no steps");
  EXPECT_EQ(ErrorOf("1 0.1 0x\n"), "drive.txt:1: '0x' is not a finite number");
}

TEST(VelocityProfileTest, StepsFollowEachOtherThenTheProfileEnds) {
  const std::vector<VelocityProfileStep> steps =
      ParseVelocityProfile("1 0.3 0\n2 0 0.5\n", "p");
  EXPECT_EQ(ProfileStepAt(steps, 0.0)->line, 1);
  EXPECT_EQ(ProfileStepAt(steps, 0.999)->line, 1);
  EXPECT_EQ(ProfileStepAt(steps, 1.0)->line, 2);
  EXPECT_EQ(ProfileStepAt(steps, 2.999)->line, 2);
  EXPECT_FALSE(ProfileStepAt(steps, 3.0).has_value());
}

std::vector<TeleopKey> Keys(const std::string& bytes) {
  TerminalKeyDecoder decoder;
  return decoder.Feed(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

TEST(TeleopKeysTest, ArrowsLettersSpaceAndQuit) {
  using K = TeleopKey;
  EXPECT_EQ(Keys("\x1b[A\x1b[B\x1b[C\x1b[D"),
            (std::vector<K>{K::kFaster, K::kSlower, K::kRight, K::kLeft}));
  EXPECT_EQ(Keys("\x1bOA\x1bOD"), (std::vector<K>{K::kFaster, K::kLeft}));
  EXPECT_EQ(Keys("wasdWASD"), (std::vector<K>{K::kFaster, K::kLeft, K::kSlower, K::kRight,
                                               K::kFaster, K::kLeft, K::kSlower, K::kRight}));
  EXPECT_EQ(Keys(" q\x03\x04"), (std::vector<K>{K::kStop, K::kQuit, K::kQuit, K::kQuit}));
  // Other keys and other escape sequences (Ctrl-arrow, F5, a lone ESC then a letter) do nothing.
  EXPECT_EQ(Keys("xz1\n\x1b[1;5A\x1b[15~"), (std::vector<K>{}));
  EXPECT_EQ(Keys("\x1bxw"), (std::vector<K>{K::kFaster}));
}

TEST(TeleopKeysTest, AnArrowSplitBetweenTwoReadsIsOneKey) {
  TerminalKeyDecoder decoder;
  const uint8_t first[] = {0x1b, '['};
  const uint8_t second[] = {'C', 'w'};
  EXPECT_TRUE(decoder.Feed(first, sizeof first).empty());
  EXPECT_EQ(decoder.Feed(second, sizeof second),
            (std::vector<TeleopKey>{TeleopKey::kRight, TeleopKey::kFaster}));
}

TEST(TeleopKeysTest, KeysStepTheCommandWithinItsLimits) {
  TeleopSteps steps;  // 0.05 m/s, 0.1 rad/s, limits 0.5 and 1
  TeleopCommand command;
  for (int i = 0; i < 3; ++i) command = ApplyTeleopKey(command, TeleopKey::kFaster, steps);
  EXPECT_NEAR(command.linear_mps, 0.15, 1e-12);
  // Back down lands on exactly 0, not on a rounding residue.
  for (int i = 0; i < 3; ++i) command = ApplyTeleopKey(command, TeleopKey::kSlower, steps);
  EXPECT_EQ(command.linear_mps, 0.0);
  for (int i = 0; i < 30; ++i) command = ApplyTeleopKey(command, TeleopKey::kSlower, steps);
  EXPECT_DOUBLE_EQ(command.linear_mps, -0.5);
  for (int i = 0; i < 30; ++i) command = ApplyTeleopKey(command, TeleopKey::kLeft, steps);
  EXPECT_DOUBLE_EQ(command.angular_radps, 1.0);
  command = ApplyTeleopKey(command, TeleopKey::kRight, steps);
  EXPECT_NEAR(command.angular_radps, 0.9, 1e-12);
  const TeleopCommand quitting = ApplyTeleopKey(command, TeleopKey::kQuit, steps);
  EXPECT_EQ(quitting.linear_mps, command.linear_mps);
  command = ApplyTeleopKey(command, TeleopKey::kStop, steps);
  EXPECT_EQ(command.linear_mps, 0.0);
  EXPECT_EQ(command.angular_radps, 0.0);
}

}  // namespace
}  // namespace slammtt
