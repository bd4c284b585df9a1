// slammtt-replay with the stack's real stages on logs of the synthetic world: byte-identical
// runs (logs with scans, with point features, with both), a stage skipped when its input is
// absent, replaying a replay changes nothing, progress lines, and slammtt-timing and slammtt-eval
// run on what it writes.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>
#include <string>
#include <vector>

#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

class ReplayStackTest : public ::testing::Test {
 protected:
  void WriteWorldLog(const std::string& name, const std::string& output_kind) {
    std::string out;
    ASSERT_EQ(Shell(Bin("slammtt-world") + " --scenario s1-crossing --seed 3 --duration 25 " +
                      "--output " + output_kind + " --log " + dir_.File(name),
                  &out),
              0)
        << out;
  }
  testing::TempDir dir_;
};

TEST_F(ReplayStackTest, TwoRunsAreByteIdenticalAndToolsReadTheOutput) {
  WriteWorldLog("world.lcm", "both");
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir_.File("world.lcm") + " -o " +
                    dir_.File("a.lcm"),
                &out),
            0)
      << out;
  EXPECT_NE(out.find("segmenter: handled 201 messages, published 201"), std::string::npos)
      << out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir_.File("world.lcm") + " -o " +
                    dir_.File("b.lcm") + " --timing-log " + dir_.File("b-timing.lcm"),
                &out),
            0)
      << out;
  const std::string a = testing::FileBytes(dir_.File("a.lcm"));
  EXPECT_GT(a.size(), 100000u);
  EXPECT_EQ(a, testing::FileBytes(dir_.File("b.lcm")));
  // The timing differs (it measures the machine) and lives apart.
  EXPECT_TRUE(testing::FileExists(dir_.File("a.lcm.timing.lcm")));

  std::map<std::string, int> channels;
  for (const LogEvent& e : testing::ReadLog(dir_.File("a.lcm"))) ++channels[e.channel];
  EXPECT_EQ(channels["LASER_SCAN"], 201);
  EXPECT_EQ(channels["FEATURES"], 201);  // recomputed, the world's replaced
  EXPECT_EQ(channels["POSE"], 201);
  EXPECT_EQ(channels["TRACKS"], 201);
  EXPECT_EQ(channels.count("STAGE_TIMING"), 0u);

  ASSERT_EQ(Shell(Bin("slammtt-timing") + " " + dir_.File("a.lcm.timing.lcm"), &out), 0) << out;
  for (const char* name : {"segmenter", "estimator", "predict", "gating", "level1", "ransac",
                           "level2_3", "track_management"}) {
    EXPECT_NE(out.find(name), std::string::npos) << name << "\n" << out;
  }
  ASSERT_EQ(Shell(Bin("slammtt-eval") + " " + dir_.File("a.lcm") + " --json " +
                    dir_.File("report.json") + " --plots " + dir_.File("plots"),
                &out),
            0)
      << out;
  const nlohmann::json j = nlohmann::json::parse(testing::FileBytes(dir_.File("report.json")));
  EXPECT_TRUE(j["ate_rmse_m"].is_number()) << out;
  EXPECT_TRUE(j["ospa_mean_m"].is_number()) << out;
  EXPECT_TRUE(testing::FileExists(dir_.File("plots/trajectory.svg")));
}

// slammtt-replay stopped by a signal in the middle of a log. Before: it ignored SIGTERM and
// SIGINT (ran to the end, exit 0, output written) and SIGKILL left its 63 MB
// out.lcm.partial.<pid> behind. The replay is held (SIGSTOP) once its output is open, so the
// signal surely arrives mid-replay, then continued.
class ReplaySignalTest : public ReplayStackTest {
 protected:
  // The files of the test directory whose names start with "out".
  std::vector<std::string> Outputs() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path())) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("out", 0) == 0) names.push_back(name);
    }
    return names;
  }
  // Whether `pid` has its output open in the test directory (named or not).
  bool WritesIntoTheDirectory(pid_t pid) const {
    const std::string fds = "/proc/" + std::to_string(pid) + "/fd";
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(fds, error)) {
      const std::string target = std::filesystem::read_symlink(entry.path(), error).string();
      // The output: out.lcm.partial.*, or an unnamed file ("DIR/#NNN (deleted)").
      if (target.rfind(dir_.path() + "/", 0) == 0 &&
          (target.find("out.lcm") != std::string::npos ||
           target.find("(deleted)") != std::string::npos)) {
        return true;
      }
    }
    return false;
  }
  std::unique_ptr<testing::ChildProcess> StartReplayAndHoldIt() {
    auto replay = std::make_unique<testing::ChildProcess>(
        std::vector<std::string>{Bin("slammtt-replay"), dir_.File("world.lcm"), "-o",
                                 dir_.File("out.lcm")},
        dir_.File("replay-out.txt"), dir_.File("replay-err.txt"));
    for (int k = 0; k < 20000 && !WritesIntoTheDirectory(replay->pid()); ++k) usleep(100);
    EXPECT_TRUE(WritesIntoTheDirectory(replay->pid()));
    replay->Signal(SIGSTOP);
    return replay;
  }
};

TEST_F(ReplaySignalTest, SigtermAndSigintStopItWithNoOutputLeft) {
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-world") + " --quiet --scenario s2-lobby --seed 2 --duration 300 " +
                      "--output scans --log " + dir_.File("world.lcm"),
                  &out),
            0)
      << out;
  for (const int signal_number : {SIGTERM, SIGINT}) {
    const auto replay = StartReplayAndHoldIt();
    replay->Signal(signal_number);
    replay->Signal(SIGCONT);
    EXPECT_EQ(replay->Wait(30000), std::optional<int>(1));
    const std::string err = testing::FileBytes(dir_.File("replay-err.txt"));
    EXPECT_NE(err.find("slammtt-replay: error: stopped after "), std::string::npos) << err;
    EXPECT_NE(err.find(" events (signal " + std::to_string(signal_number) +
                       "); no output written\n"),
              std::string::npos)
        << err;
    EXPECT_TRUE(Outputs().empty()) << Outputs().front();
  }
}

TEST_F(ReplaySignalTest, SigkillLeavesNoPartialOutput) {
  const int probe = open(dir_.path().c_str(), O_TMPFILE | O_WRONLY, 0600);
  if (probe < 0) {
    GTEST_SKIP() << dir_.path() << " has no O_TMPFILE: a killed replay leaves its partial file";
  }
  close(probe);
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-world") + " --quiet --scenario s2-lobby --seed 2 --duration 300 " +
                      "--output scans --log " + dir_.File("world.lcm"),
                  &out),
            0)
      << out;
  const auto replay = StartReplayAndHoldIt();
  replay->Signal(SIGKILL);
  EXPECT_EQ(replay->Wait(30000), std::optional<int>(128 + SIGKILL));
  EXPECT_TRUE(Outputs().empty()) << Outputs().front();
}

TEST_F(ReplayStackTest, ReplayingAReplayChangesNothing) {
  WriteWorldLog("world.lcm", "scans");
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --no-timing " + dir_.File("world.lcm") + " -o " +
                dir_.File("once.lcm")),
            0);
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --no-timing " + dir_.File("once.lcm") + " -o " +
                dir_.File("twice.lcm")),
            0);
  EXPECT_EQ(testing::FileBytes(dir_.File("once.lcm")), testing::FileBytes(dir_.File("twice.lcm")));
  EXPECT_FALSE(testing::FileExists(dir_.File("once.lcm.timing.lcm")));
}

TEST_F(ReplayStackTest, SkipsTheSegmenterOnAFeaturesOnlyLog) {
  WriteWorldLog("world.lcm", "features");
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir_.File("world.lcm") + " -o " +
                    dir_.File("out.lcm"),
                &out),
            0)
      << out;
  EXPECT_NE(out.find("segmenter: skipped"), std::string::npos) << out;
  // The world's own FEATURES are kept, byte for byte, and the estimator ran on them.
  std::vector<std::string> in_features;
  std::vector<std::string> out_features;
  int poses = 0;
  for (const LogEvent& e : testing::ReadLog(dir_.File("world.lcm"))) {
    if (e.channel == "FEATURES") in_features.emplace_back(e.data.begin(), e.data.end());
  }
  for (const LogEvent& e : testing::ReadLog(dir_.File("out.lcm"))) {
    if (e.channel == "FEATURES") out_features.emplace_back(e.data.begin(), e.data.end());
    poses += e.channel == "POSE" ? 1 : 0;
  }
  EXPECT_EQ(in_features, out_features);
  EXPECT_EQ(poses, 201);
  // Deterministic on this kind of log too.
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " " + dir_.File("world.lcm") + " -o " +
                      dir_.File("again.lcm"),
                  &out),
            0)
      << out;
  EXPECT_EQ(testing::FileBytes(dir_.File("out.lcm")), testing::FileBytes(dir_.File("again.lcm")));
}

// A long log gets progress lines ("every 5 s of log" here, for a 25 s log; 30 s by default).
TEST_F(ReplayStackTest, PrintsProgressOnLongLogs) {
  WriteWorldLog("world.lcm", "scans");
  testing::WriteFileBytes(dir_.File("progress.yaml"), "replay:\n  progress_every_log_s: 5\n");
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --no-timing --config " + dir_.File("progress.yaml") +
                      " " + dir_.File("world.lcm") + " -o " + dir_.File("out.lcm"),
                  &out),
            0)
      << out;
  size_t lines = 0;
  for (size_t at = out.find("slammtt-replay: info: replay: "); at != std::string::npos;
       at = out.find("slammtt-replay: info: replay: ", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 5u) << out;  // at 5, 10, 15, 20 and 25 s of log
  EXPECT_NE(out.find(" of 25 s of log, "), std::string::npos) << out;
}

// Overwrites the big-endian int32 at `offset` of an encoded message.
void SetInt32(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  for (int k = 0; k < 4; ++k) {
    (*bytes)[offset + k] = static_cast<uint8_t>(static_cast<uint32_t>(value) >> (24 - 8 * k));
  }
}

// Corrupt array counts in a log (what once cost the estimator 7.7 s and 2.7 GB on one FEATURES
// message) are dropped by every reader: replay, the estimator and eval run on within a 1 GB
// address space, and everything else in the log is processed as before.
TEST_F(ReplayStackTest, CorruptCountsAreDroppedWithinBoundedMemory) {
  WriteWorldLog("world.lcm", "features");
  std::vector<LogEvent> events = testing::ReadLog(dir_.File("world.lcm"));
  // num_features follows the fingerprint, utime and sequence; num_objects the fingerprint,
  // utime and five robot doubles (lcmtypes/features_t.lcm, ground_truth_t.lcm).
  // 0x02000000 features would be 1.9 GB of feature_t if believed.
  const std::vector<int32_t> corrupt_features = {-1, 0x7fffffff, 0x02000000};
  int features = 0;
  int truths = 0;
  size_t corrupted = 0;
  bool truth_corrupted = false;
  for (LogEvent& e : events) {
    if (e.channel == "FEATURES" && ++features % 20 == 0 && corrupted < corrupt_features.size()) {
      SetInt32(&e.data, 8 + 8 + 8, corrupt_features[corrupted++]);
    }
    if (e.channel == "GROUND_TRUTH" && ++truths == 30) {
      SetInt32(&e.data, 8 + 8 + 5 * 8, 0x7fffffff);
      truth_corrupted = true;
    }
  }
  ASSERT_EQ(corrupted, corrupt_features.size());
  ASSERT_TRUE(truth_corrupted);
  testing::WriteLog(dir_.File("corrupt.lcm"), events);

  std::string out;
  const std::string limit = "ulimit -v 1000000; ";  // kB
  ASSERT_EQ(Shell(limit + Bin("slammtt-replay") + " --no-timing " + dir_.File("corrupt.lcm") +
                      " -o " + dir_.File("out.lcm"),
                  &out),
            0)
      << out;
  // Dropped by Decode, not thrown out of the stage (which replay would count as "N failed").
  EXPECT_EQ(out.find(" failed"), std::string::npos) << out;
  int poses = 0;
  for (const LogEvent& e : testing::ReadLog(dir_.File("out.lcm"))) {
    poses += e.channel == "POSE" ? 1 : 0;
  }
  EXPECT_EQ(poses, features - static_cast<int>(corrupt_features.size())) << out;

  ASSERT_EQ(Shell(limit + Bin("slammtt-eval") + " " + dir_.File("out.lcm") + " --json " +
                      dir_.File("report.json"),
                  &out),
            0)
      << out;
  const nlohmann::json j = nlohmann::json::parse(testing::FileBytes(dir_.File("report.json")));
  EXPECT_EQ(j["detail"]["input"]["messages"]["ground_truth"]["rejected"], 1) << out;
  EXPECT_EQ(j["detail"]["input"]["messages"]["ground_truth"]["accepted"], truths - 1) << out;
}

TEST_F(ReplayStackTest, ConfigurationChoosesStagesAndRejectsUnknownKeys) {
  WriteWorldLog("world.lcm", "both");
  testing::WriteFileBytes(dir_.File("estimator-only.yaml"), "replay:\n  stages: [estimator]\n");
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --config " + dir_.File("estimator-only.yaml") + " " +
                    dir_.File("world.lcm") + " -o " + dir_.File("out.lcm"),
                &out),
            0)
      << out;
  EXPECT_EQ(out.find("segmenter: handled"), std::string::npos) << out;
  EXPECT_NE(out.find("estimator: handled"), std::string::npos) << out;

  testing::WriteFileBytes(dir_.File("typo.yaml"), "replay:\n  stagse: [estimator]\n");
  EXPECT_NE(Shell(Bin("slammtt-replay") + " --config " + dir_.File("typo.yaml") + " " +
                    dir_.File("world.lcm") + " -o " + dir_.File("out2.lcm"),
                &out),
            0);
  EXPECT_NE(out.find("stagse"), std::string::npos) << out;
  EXPECT_FALSE(testing::FileExists(dir_.File("out2.lcm")));
  EXPECT_NE(Shell(Bin("slammtt-replay") + " " + dir_.File("world.lcm"), &out), 0);
  EXPECT_NE(out.find("-o OUT.lcm is required"), std::string::npos) << out;
}

}  // namespace
}  // namespace slammtt
