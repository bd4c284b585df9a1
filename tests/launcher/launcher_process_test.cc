// slammtt-launch as a process, supervising small shell programs: output prefixes, restarts with
// backoff and a limit, giving up, the ordered stop on SIGTERM/SIGINT, SIGKILL after the grace
// period, configuration errors.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <optional>
#include <tuple>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ChildProcess;
using testing::ReadWholeFile;

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class LauncherProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { directory_ = testing::MakeTempDirectory("launcher-test"); }
  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "stdout:\n" << ReadWholeFile(out_) << "stderr:\n" << ReadWholeFile(err_);
    } else {
      launcher_.reset();
      testing::RemoveDirectoryTree(directory_);
    }
  }

  // Writes robot.yaml with the given robot: section body (indented by the caller).
  std::string WriteConfig(const std::string& robot_body) {
    const std::string path = directory_ + "/robot.yaml";
    std::ofstream(path) << "robot:\n  log_directory: " << directory_ << "/logs\n" << robot_body;
    return path;
  }

  // A shell snippet that records `name` in the marker file when it gets SIGTERM, then exits 0.
  std::string TermMarker(const std::string& name) const {
    return "trap 'echo " + name + " >> " + directory_ + "/stopped; exit 0' TERM; ";
  }

  void Launch(const std::string& config, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {std::string(SLAMMTT_BIN_DIR) + "/slammtt-launch", "--config",
                                     config};
    argv.insert(argv.end(), extra.begin(), extra.end());
    out_ = directory_ + "/out.log";
    err_ = directory_ + "/err.log";
    launcher_ = std::make_unique<ChildProcess>(argv, out_, err_);
  }

  // Waits until `text` shows in the launcher's stdout+stderr, at most `seconds`.
  bool WaitFor(const std::string& text, double seconds = 10.0, size_t times = 1) {
    const auto end = std::chrono::steady_clock::now() +
                     std::chrono::milliseconds(static_cast<int>(seconds * 1000));
    while (std::chrono::steady_clock::now() < end) {
      if (Count(ReadWholeFile(out_) + ReadWholeFile(err_), text) >= times) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  std::string Stopped() const { return ReadWholeFile(directory_ + "/stopped"); }

  std::string directory_;
  std::string out_;
  std::string err_;
  std::unique_ptr<ChildProcess> launcher_;
};

TEST_F(LauncherProcessTest, PrefixesEachLineOfStdoutAndStderrWithTheName) {
  Launch(WriteConfig(R"(  processes:
    - name: alpha
      program: sh
      pass_config: false
      args: ["-c", "echo one; echo two >&2; printf 'no newline'; exec sleep 30"]
    - name: b
      program: sh
      pass_config: false
      args: ["-c", "echo three; exec sleep 30"]
)"));
  ASSERT_TRUE(WaitFor("b     | three"));
  ASSERT_TRUE(WaitFor("alpha | two"));
  launcher_->Signal(SIGTERM);
  ASSERT_EQ(launcher_->Wait(10000), 0);
  const std::string out = ReadWholeFile(out_);
  const std::string err = ReadWholeFile(err_);
  EXPECT_NE(out.find("alpha | one\n"), std::string::npos);
  EXPECT_NE(out.find("alpha | no newline\n"), std::string::npos);  // flushed at the end
  EXPECT_NE(err.find("alpha | two\n"), std::string::npos);
  EXPECT_EQ(out.find("alpha | two"), std::string::npos);            // stderr stays stderr
  EXPECT_NE(err.find("slammtt-launch: info: started alpha"), std::string::npos);
}

TEST_F(LauncherProcessTest, RestartsWithBackoffThenGivesUpAndStopsTheStack) {
  Launch(WriteConfig(R"(  max_restarts: 2
  restart_initial_s: 0.2
  processes:
    - name: steady
      program: sh
      pass_config: false
      args: ["-c", ")" + TermMarker("steady") + R"(while :; do sleep 0.05; done"]
    - name: crasher
      program: sh
      pass_config: false
      args: ["-c", "echo dying; exit 3"]
)"));
  const auto status = launcher_->Wait(20000);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 1);
  const std::string out = ReadWholeFile(out_);
  const std::string err = ReadWholeFile(err_);
  EXPECT_EQ(Count(out, "crasher | dying"), 3u);  // the first run and 2 restarts
  EXPECT_NE(err.find("restarting in 0.2 s"), std::string::npos);
  EXPECT_NE(err.find("restarting in 0.4 s"), std::string::npos);
  EXPECT_NE(err.find("giving up on it after 2 restarts in a row: stopping the stack"),
            std::string::npos);
  EXPECT_EQ(Stopped(), "steady\n");
}

TEST_F(LauncherProcessTest, KeepRunningLeavesTheOthersUpAndStillExitsNonZero) {
  Launch(WriteConfig(R"(  max_restarts: 0
  on_give_up: keep_running
  processes:
    - name: steady
      program: sh
      pass_config: false
      args: ["-c", ")" + TermMarker("steady") + R"(while :; do sleep 0.05; done"]
    - name: crasher
      program: sh
      pass_config: false
      args: ["-c", "exit 7"]
)"));
  ASSERT_TRUE(WaitFor("giving up"));
  EXPECT_FALSE(launcher_->Wait(500).has_value());  // still supervising steady
  EXPECT_EQ(Stopped(), "");
  launcher_->Signal(SIGTERM);
  EXPECT_EQ(launcher_->Wait(10000), 1);
  EXPECT_EQ(Stopped(), "steady\n");
}

TEST_F(LauncherProcessTest, SigtermStopsEveryProcessStopLastOnesAfterTheOthers) {
  Launch(WriteConfig(R"(  processes:
    - name: logger
      program: sh
      pass_config: false
      stop_last: true
      args: ["-c", ")" + TermMarker("logger") + R"(while :; do sleep 0.05; done"]
    - name: a
      program: sh
      pass_config: false
      args: ["-c", ")" + TermMarker("a") + R"(while :; do sleep 0.05; done"]
    - name: b
      program: sh
      pass_config: false
      args: ["-c", "trap 'sleep 0.3; echo b >> )" + directory_ + R"(/stopped; exit 0' TERM; while :; do sleep 0.05; done"]
)"));
  ASSERT_TRUE(WaitFor("started b"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  launcher_->Signal(SIGTERM);
  ASSERT_EQ(launcher_->Wait(10000), 0);
  const std::string stopped = Stopped();
  // a and b in any order (b takes 0.3 s), the logger strictly after both.
  EXPECT_EQ(stopped.size(), std::string("a\nb\nlogger\n").size()) << stopped;
  EXPECT_EQ(stopped.substr(stopped.size() - 7), "logger\n") << stopped;
  EXPECT_NE(ReadWholeFile(err_).find("stopping (signal 15)"), std::string::npos);
}

TEST_F(LauncherProcessTest, SigintStopsLikeSigterm) {
  Launch(WriteConfig(R"(  processes:
    - name: a
      program: sh
      pass_config: false
      args: ["-c", ")" + TermMarker("a") + R"(while :; do sleep 0.05; done"]
)"));
  ASSERT_TRUE(WaitFor("started a"));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  launcher_->Signal(SIGINT);
  ASSERT_EQ(launcher_->Wait(10000), 0);
  EXPECT_EQ(Stopped(), "a\n");
}

TEST_F(LauncherProcessTest, AProcessThatIgnoresSigtermIsKilledAfterTheGracePeriod) {
  Launch(WriteConfig(R"(  stop_grace_s: 0.5
  processes:
    - name: stubborn
      program: sh
      pass_config: false
      args: ["-c", "trap '' TERM; echo ready; while :; do sleep 0.05; done"]
)"));
  ASSERT_TRUE(WaitFor("stubborn | ready"));
  const auto start = std::chrono::steady_clock::now();
  launcher_->Signal(SIGTERM);
  ASSERT_EQ(launcher_->Wait(10000), 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(seconds, 0.45);
  EXPECT_NE(ReadWholeFile(err_).find("stubborn did not stop within 0.5 s of SIGTERM: SIGKILL"),
            std::string::npos);
}

TEST_F(LauncherProcessTest, ProcessesGetTheConfigAndExpandedArguments) {
  const std::string script = directory_ + "/show-args";
  std::ofstream(script) << "#!/bin/sh\necho \"args: $*\"\nexec sleep 30\n";
  chmod(script.c_str(), 0755);
  const std::string config = WriteConfig(R"(  processes:
    - name: shown
      program: )" + script + R"(
      args: ["--url={lcm_url}", "--log", "{log_file}", "{{x}}"]
)");
  Launch(config);
  ASSERT_TRUE(WaitFor("shown | args:"));
  launcher_->Signal(SIGTERM);
  ASSERT_EQ(launcher_->Wait(10000), 0);
  const std::string out = ReadWholeFile(out_);
  const std::string expected_start = "shown | args: --config " + config +
                                     " --url=udpm://239.255.76.67:7667?ttl=0 --log " + directory_ +
                                     "/logs/slammtt-";
  EXPECT_NE(out.find(expected_start), std::string::npos) << out;
  EXPECT_NE(out.find(".lcm {x}\n"), std::string::npos) << out;
  struct stat info = {};
  EXPECT_EQ(stat((directory_ + "/logs").c_str(), &info), 0);  // created by the launcher
}

TEST_F(LauncherProcessTest, EndsWhenEveryProcessFinishedCleanly) {
  Launch(WriteConfig(R"(  processes:
    - {name: one, program: sh, pass_config: false, args: ["-c", "exit 0"]}
    - {name: two, program: sh, pass_config: false, args: ["-c", "sleep 0.2"]}
)"));
  EXPECT_EQ(launcher_->Wait(10000), 0);
  EXPECT_NE(ReadWholeFile(err_).find("every process has ended"), std::string::npos);
}

TEST_F(LauncherProcessTest, ConfigurationMistakesStopBeforeAnythingStarts) {
  Launch(WriteConfig("  processes:\n    - {name: a, program: sh, colour: red}\n"));
  EXPECT_EQ(launcher_->Wait(10000), 1);
  std::string err = ReadWholeFile(err_);
  EXPECT_NE(err.find("robot.processes[0].colour"), std::string::npos) << err;
  EXPECT_EQ(Count(err, "\n"), 1u) << err;

  Launch(WriteConfig("  processes:\n    - {name: a, program: no-such-program-here}\n"));
  EXPECT_EQ(launcher_->Wait(10000), 1);
  err = ReadWholeFile(err_);
  EXPECT_NE(err.find("no-such-program-here: not found"), std::string::npos) << err;
  EXPECT_EQ(err.find("started"), std::string::npos);

  Launch(directory_ + "/missing.yaml");
  EXPECT_EQ(launcher_->Wait(10000), 1);

  const std::string bin = std::string(SLAMMTT_BIN_DIR) + "/slammtt-launch";
  ChildProcess no_config({bin}, directory_ + "/none.log");
  EXPECT_EQ(no_config.Wait(10000), 2);
}

TEST_F(LauncherProcessTest, DryRunPrintsTheCommandLines) {
  Launch(WriteConfig(R"(  processes:
    - {name: a, program: sh, args: ["-x"]}
)"), {"--dry-run"});
  ASSERT_EQ(launcher_->Wait(10000), 0);
  const std::string out = ReadWholeFile(out_);
  EXPECT_NE(out.find("/sh --config " + directory_ + "/robot.yaml -x\n"), std::string::npos) << out;
  struct stat info = {};
  EXPECT_NE(stat((directory_ + "/logs").c_str(), &info), 0);  // a dry run creates nothing

  // --lcm-url on the launcher's command line moves every pass_config process along.
  Launch(directory_ + "/robot.yaml", {"--dry-run", "--lcm-url", "udpm://239.255.76.67:7668?ttl=0"});
  ASSERT_EQ(launcher_->Wait(10000), 0);
  EXPECT_NE(ReadWholeFile(out_).find("/sh --config " + directory_ +
                                     "/robot.yaml --lcm-url udpm://239.255.76.67:7668?ttl=0 -x\n"),
            std::string::npos)
      << ReadWholeFile(out_);
}

TEST_F(LauncherProcessTest, AnUnusableLogDirectoryStopsBeforeAnythingStarts) {
  const std::string path = directory_ + "/robot.yaml";
  std::ofstream(path) << "robot:\n  log_directory: /proc/no-logs-here\n  processes:\n"
                         "    - {name: a, program: sh, pass_config: false, args: ['-c', 'echo ran']}\n";
  Launch(path);
  EXPECT_EQ(launcher_->Wait(10000), 1);
  const std::string all = ReadWholeFile(out_) + ReadWholeFile(err_);
  EXPECT_NE(all.find("cannot create the log directory /proc/no-logs-here"), std::string::npos) << all;
  EXPECT_EQ(all.find("ran"), std::string::npos);
}

// Before: the launcher only checked that no file of the name existed, so a dangling link
// planted at the next name was followed by lcm-logger and the log created at its target. Now
// the launcher creates the log file itself, exclusively: a taken name (file or link) is skipped.
TEST_F(LauncherProcessTest, APlantedLinkAtTheLogFileNameIsNeverFollowed) {
  const std::string logs = directory_ + "/logs";
  ASSERT_EQ(mkdir(logs.c_str(), 0755), 0);
  const std::string target = directory_ + "/planted-target";
  const std::string victim = directory_ + "/victim";
  std::ofstream(victim) << "precious\n";
  // Links at this second's name and the next few: dangling ones and one onto a file.
  const std::time_t now = std::time(nullptr);
  for (int k = 0; k < 4; ++k) {
    const std::time_t t = now + k;
    std::tm local = {};
    localtime_r(&t, &local);
    char name[64];
    std::strftime(name, sizeof name, "slammtt-%Y%m%d-%H%M%S.lcm", &local);
    const std::string link = logs + "/" + name;
    ASSERT_EQ(symlink((k == 0 ? victim : target).c_str(), link.c_str()), 0);
  }
  Launch(WriteConfig(R"(  processes:
    - name: logger
      program: sh
      pass_config: false
      restart: never
      args: ["-c", "echo logged > \"$0\"; echo \"wrote $0\"", "{log_file}"]
)"));
  ASSERT_EQ(launcher_->Wait(10000), 0);
  EXPECT_EQ(ReadWholeFile(victim), "precious\n");
  struct stat info = {};
  EXPECT_NE(lstat(target.c_str(), &info), 0) << "the log went through a planted link";
  const std::string out = ReadWholeFile(out_);
  const size_t at = out.find("wrote ");
  ASSERT_NE(at, std::string::npos) << out;
  const std::string written = out.substr(at + 6, out.find('\n', at) - at - 6);
  ASSERT_EQ(lstat(written.c_str(), &info), 0) << written;
  EXPECT_TRUE(S_ISREG(info.st_mode)) << written;
  EXPECT_EQ(ReadWholeFile(written), "logged\n");
}

TEST_F(LauncherProcessTest, ALogDirectoryOthersMayWriteIsRefused) {
  const std::string logs = directory_ + "/logs";
  ASSERT_EQ(mkdir(logs.c_str(), 0755), 0);
  ASSERT_EQ(chmod(logs.c_str(), 0777), 0);
  Launch(WriteConfig("  processes:\n"
                     "    - {name: a, program: sh, pass_config: false, args: ['-c', 'echo ran']}\n"));
  EXPECT_EQ(launcher_->Wait(10000), 1);
  const std::string all = ReadWholeFile(out_) + ReadWholeFile(err_);
  EXPECT_NE(all.find("is writable by other users"), std::string::npos) << all;
  EXPECT_EQ(all.find("ran"), std::string::npos);
  ASSERT_EQ(chmod(logs.c_str(), 01777), 0);  // sticky, as /tmp: nobody can swap our files
  Launch(directory_ + "/robot.yaml");
  EXPECT_EQ(launcher_->Wait(10000), 0);
}

// robot.network: loopback (the default) needs a bus that stays on the computer, routed on lo.
TEST_F(LauncherProcessTest, TheLoopbackSetupRefusesABusTheLanCanReach) {
  const std::string body =
      "  processes:\n    - {name: a, program: sh, pass_config: false, args: ['-c', 'echo ran']}\n";
  const auto launch_with = [&](const std::string& head) {
    const std::string path = directory_ + "/robot.yaml";
    std::ofstream(path) << head << "robot:\n  log_directory: " << directory_ << "/logs\n" << body;
    Launch(path);
    const std::optional<int> status = launcher_->Wait(10000);
    return std::make_pair(status.value_or(-1), ReadWholeFile(out_) + ReadWholeFile(err_));
  };
  auto [status, all] = launch_with("lcm:\n  url: \"udpm://239.255.76.67:7667?ttl=1\"\n");
  EXPECT_EQ(status, 1);
  EXPECT_NE(all.find("robot.network is loopback but the bus 'udpm://239.255.76.67:7667?ttl=1' "
                     "sends its packets beyond this computer"),
            std::string::npos)
      << all;
  EXPECT_EQ(Count(all, "\n"), 1u) << all;
  std::tie(status, all) = launch_with("lcm:\n  url: \"udpm://239.255.76.67:7667?tll=0\"\n");
  EXPECT_EQ(status, 1);
  EXPECT_NE(all.find("unknown option 'tll'"), std::string::npos) << all;

  // The group routed on another interface (a veth pair in this test's network namespace, as a
  // robot whose default route points at its LAN): refused, naming the interface.
  ASSERT_EQ(testing::Shell("ip link add slammtt-lan type veth peer name slammtt-peer && "
                           "ip addr add 10.78.0.1/24 dev slammtt-lan && ip link set slammtt-lan up "
                           "&& ip link set slammtt-peer up && "
                           "ip route replace 224.0.0.0/4 dev slammtt-lan"),
            0);
  std::tie(status, all) = launch_with("");
  EXPECT_EQ(status, 1);
  EXPECT_NE(all.find("the LCM group 239.255.76.67 is routed on slammtt-lan (10.78.0.1)"),
            std::string::npos)
      << all;
  // The same robot, told its bus is for the LAN: starts.
  const std::string path = directory_ + "/robot.yaml";
  std::ofstream(path) << "lcm:\n  url: \"udpm://239.255.76.67:7667?ttl=1\"\n"
                      << "robot:\n  network: lan\n"
                      << "  log_directory: " << directory_ << "/logs\n" << body;
  Launch(path);
  EXPECT_EQ(launcher_->Wait(10000), 0);
  EXPECT_NE(ReadWholeFile(out_).find("a | ran"), std::string::npos) << ReadWholeFile(out_);
}

}  // namespace
}  // namespace slammtt
