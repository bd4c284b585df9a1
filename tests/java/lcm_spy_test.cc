// build/bin/slammtt-lcm-spy (tools/spy/slammtt-lcm-spy.in): without a display it says so in one
// line and exits 1; on a display (Xvfb) lcm-spy starts with every slammtt type on its class path
// and keeps running until it is stopped. Runs in a network namespace of its own (lcm-spy joins
// the bus, with ttl=0).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <csignal>
#include <filesystem>
#include <string>

#include "tests/support/child_process.h"

namespace slammtt {
namespace {

namespace fs = std::filesystem;
using testing::ChildProcess;
using testing::ReadWholeFile;
using testing::TempDir;

const std::string kSpy = std::string(SLAMMTT_BIN_DIR) + "/slammtt-lcm-spy";
constexpr const char* kBusUrl = "--lcm-url=udpm://239.255.76.67:7667?ttl=0";

// Waits (bounded) until `path` holds `text`; false when it never came.
bool WaitForText(const std::string& path, const std::string& text, int timeout_ms,
                 ChildProcess* process) {
  for (int waited_ms = 0; waited_ms < timeout_ms; waited_ms += 100) {
    if (ReadWholeFile(path).find(text) != std::string::npos) return true;
    if (process->Wait(100).has_value()) {
      return ReadWholeFile(path).find(text) != std::string::npos;
    }
  }
  return false;
}

TEST(LcmSpyTest, WithoutADisplaySaysSoInOneLineAndExits1) {
  std::string output;
  const int status = testing::Shell(
      "env -u DISPLAY -u WAYLAND_DISPLAY " + kSpy + " " + kBusUrl + " 2>&1", &output);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  EXPECT_EQ(output.find('\n'), output.size() - 1) << "one line, got: " << output;
  EXPECT_EQ(output.rfind("slammtt-lcm-spy: error: no display", 0), 0u) << output;
  EXPECT_NE(output.find("xvfb-run"), std::string::npos) << output;
  EXPECT_NE(output.find("ssh -X"), std::string::npos) << output;
}

TEST(LcmSpyTest, StartsOnAnXvfbDisplayWithEveryTypeAndRunsUntilStopped) {
  if (std::string(SLAMMTT_JAVA_EXECUTABLE).empty()) {
    GTEST_SKIP() << "configured without Java, missing:" SLAMMTT_JAVA_MISSING
                    ": scripts/install-deps.sh installs it, then configure again";
  }
  int found = 0;
  testing::RunCommand("command -v Xvfb >/dev/null", &found);
  if (found != 0) GTEST_SKIP() << "no Xvfb (Debian package xvfb: scripts/install-deps.sh)";
  int lcm_types = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SLAMMTT_SOURCE_DIR) / "lcmtypes")) {
    if (entry.path().extension() == ".lcm") ++lcm_types;
  }

  TempDir dir("slammtt-lcm-spy");
  // -displayfd 1: Xvfb takes a free display number and writes it to stdout once it serves.
  ChildProcess xvfb({"Xvfb", "-displayfd", "1", "-nolisten", "tcp"}, dir.File("xvfb.out"),
                    dir.File("xvfb.err"));
  ASSERT_TRUE(WaitForText(dir.File("xvfb.out"), "\n", 30000, &xvfb))
      << "Xvfb gave no display: " << ReadWholeFile(dir.File("xvfb.err"));
  std::string display = ReadWholeFile(dir.File("xvfb.out"));
  display = ":" + display.substr(0, display.find('\n'));

  ChildProcess spy({"env", "-u", "WAYLAND_DISPLAY", "DISPLAY=" + display, kSpy, kBusUrl},
                   dir.File("spy.out"));
  // lcm.spy.Spy prints how many LCM types it found on the class path before it opens its window.
  const std::string found_types = "Found " + std::to_string(lcm_types) + " LCM types";
  EXPECT_TRUE(WaitForText(dir.File("spy.out"), found_types, 60000, &spy))
      << ReadWholeFile(dir.File("spy.out"));
  EXPECT_FALSE(spy.Wait(3000).has_value())
      << "lcm-spy ended by itself: " << ReadWholeFile(dir.File("spy.out"));
  spy.Signal(SIGTERM);
  EXPECT_TRUE(spy.Wait(10000).has_value());
  const std::string output = ReadWholeFile(dir.File("spy.out"));
  EXPECT_EQ(output.find("Exception"), std::string::npos) << output;
  xvfb.Signal(SIGTERM);
  xvfb.Wait(10000);
}

}  // namespace
}  // namespace slammtt
