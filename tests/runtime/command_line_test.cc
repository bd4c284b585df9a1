#include "runtime/command_line.h"

#include <gtest/gtest.h>

#include "runtime/process.h"

namespace slammtt {
namespace {

CommandLine MakeCommandLine() {
  CommandLine cl("prog", "[options] IN", "Test program.");
  cl.AddOption("seed", "N", "seed");
  cl.AddOption("output", "FILE", "output", 'o');
  cl.AddFlag("fast", "go fast");
  cl.AddRepeatedOption("channel", "K=V", "channel");
  cl.AddPositional("IN", "input");
  return cl;
}

TEST(CommandLineTest, ParsesOptionsFlagsAndPositionals) {
  CommandLine cl = MakeCommandLine();
  const char* argv[] = {"prog", "--seed", "7", "-o", "out.lcm", "--fast", "in.lcm",
                        "--channel=a=B", "--channel", "c=D"};
  ASSERT_TRUE(cl.Parse(10, argv));
  EXPECT_EQ(cl.IntValue("seed"), 7);
  EXPECT_EQ(cl.Value("output"), "out.lcm");
  EXPECT_TRUE(cl.Flag("fast"));
  EXPECT_EQ(cl.Positional("IN"), "in.lcm");
  EXPECT_EQ(cl.Values("channel"), (std::vector<std::string>{"a=B", "c=D"}));
}

TEST(CommandLineTest, RejectsUnknownAndIncompleteOptions) {
  CommandLine cl = MakeCommandLine();
  const char* unknown[] = {"prog", "--sed", "7", "in"};
  EXPECT_THROW(cl.Parse(4, unknown), UsageError);
  const char* no_value[] = {"prog", "in", "--seed"};
  EXPECT_THROW(cl.Parse(3, no_value), UsageError);
  const char* missing_positional[] = {"prog", "--fast"};
  EXPECT_THROW(cl.Parse(2, missing_positional), UsageError);
  const char* twice[] = {"prog", "--seed", "1", "--seed", "2", "in"};
  EXPECT_THROW(cl.Parse(6, twice), UsageError);
  const char* not_a_number[] = {"prog", "--seed", "x7", "in"};
  ASSERT_TRUE(cl.Parse(4, not_a_number));
  EXPECT_THROW(cl.IntValue("seed"), UsageError);
}

TEST(CommandLineTest, HelpReturnsFalse) {
  CommandLine cl = MakeCommandLine();
  const char* argv[] = {"prog", "--help"};
  testing::internal::CaptureStdout();
  EXPECT_FALSE(cl.Parse(2, argv));
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("--seed N"), std::string::npos);
}

TEST(ProcessMainTest, MapsErrorsToExitStatus) {
  char name[] = "prog";
  char* argv[] = {name, nullptr};
  EXPECT_EQ(ProcessMain(1, argv, "prog", [](int, char**) { return 0; }), 0);
  EXPECT_EQ(ProcessMain(1, argv, "prog", [](int, char**) -> int { throw UsageError("bad"); }), 2);
  EXPECT_EQ(ProcessMain(1, argv, "prog",
                        [](int, char**) -> int { throw std::runtime_error("broken"); }),
            1);
}

}  // namespace
}  // namespace slammtt
