#include "runtime/command_line.h"

#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>

#include <stdexcept>

#include "runtime/log.h"
#include "runtime/process.h"
#include "runtime/shutdown.h"

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

TEST(CommandLineTest, VersionPrintsTheProgramAndTheProjectVersionAndReturnsFalse) {
  CommandLine cl = MakeCommandLine();
  const char* argv[] = {"prog", "--version"};
  testing::internal::CaptureStdout();
  EXPECT_FALSE(cl.Parse(2, argv));
  EXPECT_EQ(testing::internal::GetCapturedStdout(), cl.program() + " " + SlammttVersion() + "\n");
  EXPECT_STREQ(SlammttVersion(), SLAMMTT_TEST_PROJECT_VERSION);
}

TEST(LogTest, RepeatedProblemsAreReportedAtPowersOfTen) {
  std::vector<int64_t> reported;
  for (int64_t n = -1; n <= 1000; ++n) {
    if (IsReportable(n)) reported.push_back(n);
  }
  EXPECT_EQ(reported, (std::vector<int64_t>{1, 10, 100, 1000}));
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

// Every error of a process body is one line "<program>: error: <message>" on stderr (a newline
// inside the message included) and a non-zero status.
TEST(ProcessMainTest, FatalErrorIsOneLineNamingTheProgram) {
  char name[] = "prog";
  char* argv[] = {name, nullptr};
  testing::internal::CaptureStderr();
  const int status = ProcessMain(1, argv, "slammtt-test", [](int, char**) -> int {
    throw std::runtime_error("config.yaml:3: lcm.url: expected a text value,\ngot a list");
  });
  EXPECT_EQ(status, 1);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "slammtt-test: error: config.yaml:3: lcm.url: expected a text value, got a list\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(ProcessMain(1, argv, "slammtt-test",
                        [](int, char**) -> int { throw UsageError("unknown option --x"); }),
            2);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "slammtt-test: error: unknown option --x\n");
}

bool Readable(int fd) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, 0) == 1 && (p.revents & POLLIN) != 0;
}

// SIGINT and SIGTERM only set the flag that loops poll (and wake poll() loops through the fd):
// the process lives on to stop its devices and exit normally.
TEST(ShutdownTest, SignalsSetTheFlagWakeTheFdAndCanBeReset) {
  InstallShutdownHandlers();
  for (const int signal_number : {SIGINT, SIGTERM}) {
    ResetShutdown();
    EXPECT_FALSE(ShutdownRequested());
    EXPECT_FALSE(Readable(ShutdownFd()));
    ASSERT_EQ(raise(signal_number), 0);
    EXPECT_TRUE(ShutdownRequested());
    EXPECT_EQ(ShutdownSignal(), signal_number);
    EXPECT_TRUE(Readable(ShutdownFd()));
  }
  ResetShutdown();
  RequestShutdown();
  EXPECT_TRUE(ShutdownRequested());
  EXPECT_EQ(ShutdownSignal(), 0);
  ResetShutdown();
  EXPECT_FALSE(ShutdownRequested());
  EXPECT_FALSE(Readable(ShutdownFd()));
}

}  // namespace
}  // namespace slammtt
