#include "tools/replay/log_replay.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "slammtt_msgs/stage_timing_t.hpp"
#include "tests/support/options_table.h"
#include "tests/tools/log_test_util.h"
#include "tools/replay/replay_config.h"

namespace slammtt {
namespace {

using testing::Bytes;
using testing::FileBytes;
using testing::FileExists;
using testing::ReadLog;
using testing::TempDir;
using testing::WriteLog;

std::string Text(const LogEvent& e) { return std::string(e.data.begin(), e.data.end()); }

// Stands in for the segmenter: "SCAN" in, "FEAT" out (the payload reversed, with a counter).
class FakeSegmenter : public Stage {
 public:
  std::string Name() const override { return "fake_segmenter"; }
  std::vector<std::string> InputChannels() const override { return {"SCAN"}; }
  std::vector<std::string> OutputChannels() const override { return {"FEAT"}; }
  void Handle(const std::string&, const void* data, int size, MessageSink& out) override {
    StageTimer timer(Name(), 0);
    const auto* bytes = static_cast<const char*>(data);
    std::string features(bytes, bytes + size);
    std::reverse(features.begin(), features.end());
    features += "#" + std::to_string(++count_);
    timer.Lap("split");
    out.Publish("FEAT", features.data(), static_cast<int>(features.size()));
    out.PublishMessage("STAGE_TIMING", timer.Finish());
  }

 private:
  int count_ = 0;
};

// Stands in for the estimator: "ODOM" and "FEAT" in; after each "FEAT" it publishes on "EST" a
// digest of everything it has received so far, so any change of order or content shows.
class FakeEstimator : public Stage {
 public:
  std::string Name() const override { return "fake_estimator"; }
  std::vector<std::string> InputChannels() const override { return {"ODOM", "FEAT"}; }
  std::vector<std::string> OutputChannels() const override { return {"EST"}; }
  void Handle(const std::string& channel, const void* data, int size, MessageSink& out) override {
    StageTimer timer(Name(), 0);
    const auto* bytes = static_cast<const char*>(data);
    history_ += channel + ":" + std::string(bytes, bytes + size) + ";";
    if (channel != "FEAT") return;
    if (std::string(bytes, bytes + size) == "boom") throw std::runtime_error("bad features");
    out.Publish("EST", history_.data(), static_cast<int>(history_.size()));
    out.PublishMessage("STAGE_TIMING", timer.Finish());
  }

 private:
  std::string history_;
};

std::vector<std::unique_ptr<Stage>> FakeStack() {
  std::vector<std::unique_ptr<Stage>> stages;
  stages.push_back(std::make_unique<FakeSegmenter>());
  stages.push_back(std::make_unique<FakeEstimator>());
  return stages;
}

LogEvent Event(int64_t t, const std::string& channel, const std::string& text) {
  LogEvent e;
  e.timestamp_us = t;
  e.channel = channel;
  e.data = Bytes(text);
  return e;
}

// A recording of a live run: scans, odometry, truth, the live FEAT and a live STAGE_TIMING.
std::vector<LogEvent> LiveLikeLog() {
  return {Event(100, "ODOM", "o1"),    Event(110, "SCAN", "abc"),  Event(111, "FEAT", "live"),
          Event(112, "TRUTH", "t1"),   Event(150, "ODOM", "o2"),   Event(160, "STAGE_TIMING", "x"),
          Event(210, "SCAN", "de"),    Event(212, "TRUTH", "t2"),  Event(250, "ODOM", "o3")};
}

ReplayFileOptions Options(const TempDir& dir) {
  ReplayFileOptions options;
  options.timing_path = dir.File("out.timing.lcm");
  return options;
}

TEST(ReplayTest, RunsStagesInLogOrderAndReplacesTheirOutputs) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.warning.empty());
  EXPECT_EQ(r.events_read, 9);
  ASSERT_EQ(r.stages.size(), 2u);
  EXPECT_TRUE(r.stages[0].runs);
  EXPECT_TRUE(r.stages[1].runs);
  EXPECT_EQ(r.replaced_channels, (std::set<std::string>{"FEAT", "EST", "STAGE_TIMING"}));

  const std::vector<LogEvent> out = ReadLog(dir.File("out.lcm"));
  std::vector<std::string> lines;
  for (const LogEvent& e : out) {
    lines.push_back(std::to_string(e.timestamp_us) + " " + e.channel + " " + Text(e));
  }
  // Inputs copied with their timestamps; the live FEAT and STAGE_TIMING replaced; outputs right
  // after their input, stamped with its timestamp; the segmenter's FEAT reached the estimator.
  const std::vector<std::string> expected = {
      "100 ODOM o1",
      "110 SCAN abc",
      "110 FEAT cba#1",
      "110 EST ODOM:o1;FEAT:cba#1;",
      "112 TRUTH t1",
      "150 ODOM o2",
      "210 SCAN de",
      "210 FEAT ed#2",
      "210 EST ODOM:o1;FEAT:cba#1;ODOM:o2;FEAT:ed#2;",
      "212 TRUTH t2",
      "250 ODOM o3"};
  EXPECT_EQ(lines, expected);
  EXPECT_EQ(r.events_written, static_cast<int64_t>(expected.size()));

  // Timing went to its own log, decodable, one per stage call that published one.
  const std::vector<LogEvent> timing = ReadLog(dir.File("out.timing.lcm"));
  ASSERT_EQ(timing.size(), 4u);
  std::map<std::string, int> per_stage;
  for (const LogEvent& e : timing) {
    slammtt_msgs::stage_timing_t msg;
    ASSERT_TRUE(Decode(e.data.data(), static_cast<int>(e.data.size()), &msg));
    ++per_stage[msg.stage];
  }
  EXPECT_EQ(per_stage["fake_segmenter"], 2);
  EXPECT_EQ(per_stage["fake_estimator"], 2);
  EXPECT_EQ(timing[0].timestamp_us, 110);
}

// Publishes two FEAT messages per SCAN.
class DoubleSegmenter : public Stage {
 public:
  std::string Name() const override { return "double"; }
  std::vector<std::string> InputChannels() const override { return {"SCAN"}; }
  std::vector<std::string> OutputChannels() const override { return {"FEAT"}; }
  void Handle(const std::string&, const void*, int, MessageSink& out) override {
    out.Publish("FEAT", "x1", 2);
    out.Publish("FEAT", "x2", 2);
  }
};

TEST(ReplayTest, ConsumersRunOnceTheProducerHasReturned) {
  // As separate processes would: the estimator sees the segmenter's outputs after the segmenter
  // is done with the scan, so all of the segmenter's outputs come first.
  TempDir dir;
  WriteLog(dir.File("in.lcm"), {Event(7, "SCAN", "s")});
  std::vector<std::unique_ptr<Stage>> stages;
  stages.push_back(std::make_unique<DoubleSegmenter>());
  stages.push_back(std::make_unique<FakeEstimator>());
  ASSERT_TRUE(ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), std::move(stages),
                            ReplayFileOptions())
                  .error.empty());
  std::vector<std::string> lines;
  for (const LogEvent& e : ReadLog(dir.File("out.lcm"))) lines.push_back(e.channel + " " + Text(e));
  EXPECT_EQ(lines, (std::vector<std::string>{"SCAN s", "FEAT x1", "FEAT x2", "EST FEAT:x1;",
                                             "EST FEAT:x1;FEAT:x2;"}));
}

TEST(ReplayTest, TwoRunsGiveIdenticalBytes) {
  TempDir dir;
  std::vector<LogEvent> events;
  for (int k = 0; k < 500; ++k) {
    events.push_back(Event(1000 * k, "ODOM", "odometry " + std::to_string(k)));
    if (k % 3 == 0) events.push_back(Event(1000 * k + 5, "SCAN", "scan " + std::to_string(k)));
    if (k % 7 == 0) events.push_back(Event(1000 * k + 6, "TRUTH", std::string(k % 50, 'g')));
  }
  WriteLog(dir.File("in.lcm"), events);
  ReplayFileOptions first = Options(dir);
  ASSERT_TRUE(
      ReplayLogFile(dir.File("in.lcm"), dir.File("a.lcm"), FakeStack(), first).error.empty());
  ReplayFileOptions second;
  second.timing_path = dir.File("b.timing.lcm");
  ASSERT_TRUE(
      ReplayLogFile(dir.File("in.lcm"), dir.File("b.lcm"), FakeStack(), second).error.empty());
  const std::string a = FileBytes(dir.File("a.lcm"));
  EXPECT_GT(a.size(), 10000u);
  EXPECT_EQ(a, FileBytes(dir.File("b.lcm")));
}

TEST(ReplayTest, SkipsAStageWhoseInputIsAbsent) {
  // A FEATURES-only log (as the synthetic world writes): no SCAN, so the segmenter does not run,
  // the input FEAT is kept and the estimator runs on it.
  TempDir dir;
  WriteLog(dir.File("in.lcm"), {Event(1, "ODOM", "o"), Event(2, "FEAT", "f1"),
                                Event(3, "TRUTH", "t"), Event(4, "FEAT", "f2")});
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.stages[0].runs);
  EXPECT_EQ(r.stages[0].messages_handled, 0);
  EXPECT_TRUE(r.stages[1].runs);
  const std::vector<LogEvent> out = ReadLog(dir.File("out.lcm"));
  ASSERT_EQ(out.size(), 6u);
  EXPECT_EQ(out[1].channel, "FEAT");
  EXPECT_EQ(Text(out[1]), "f1");
  EXPECT_EQ(out[2].channel, "EST");
  EXPECT_EQ(Text(out[5]), "ODOM:o;FEAT:f1;FEAT:f2;");
}

TEST(ReplayTest, ADroppedChannelIsNeitherCopiedNorHandedToAStage) {
  // --drop-channel ODOM: a robot without odometry. The estimator still runs (FEAT), sees no
  // ODOM, and the output holds none; a stage whose only input is dropped does not run.
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  ReplayFileOptions options = Options(dir);
  options.dropped_channels = {"ODOM"};
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), options);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.events_read, 9);
  std::vector<std::string> lines;
  for (const LogEvent& e : ReadLog(dir.File("out.lcm"))) {
    lines.push_back(std::to_string(e.timestamp_us) + " " + e.channel + " " + Text(e));
  }
  const std::vector<std::string> expected = {
      "110 SCAN abc", "110 FEAT cba#1", "110 EST FEAT:cba#1;", "112 TRUTH t1",
      "210 SCAN de",  "210 FEAT ed#2",  "210 EST FEAT:cba#1;FEAT:ed#2;", "212 TRUTH t2"};
  EXPECT_EQ(lines, expected);

  options.dropped_channels = {"SCAN"};
  const ReplayFileResult without_scans =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out2.lcm"), FakeStack(), options);
  ASSERT_TRUE(without_scans.error.empty()) << without_scans.error;
  EXPECT_FALSE(without_scans.stages[0].runs);
  EXPECT_EQ(without_scans.stages[0].messages_handled, 0);
}

TEST(ReplayTest, WithoutAnyStageInputTheLogIsCopied) {
  TempDir dir;
  const std::vector<LogEvent> in = {Event(1, "TRUTH", "t"), Event(2, "STAGE_TIMING", "live"),
                                    Event(3, "OTHER", "x")};
  WriteLog(dir.File("in.lcm"), in);
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.stages[0].runs);
  EXPECT_FALSE(r.stages[1].runs);
  EXPECT_EQ(FileBytes(dir.File("out.lcm")), FileBytes(dir.File("in.lcm")));
  EXPECT_TRUE(ReadLog(dir.File("out.timing.lcm")).empty());
}

TEST(ReplayTest, NoTimingLogWhenNotAsked) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  ReplayFileOptions options;  // no timing path
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), options);
  ASSERT_TRUE(r.error.empty());
  EXPECT_EQ(r.timing_events_written, 0);
  EXPECT_EQ(r.stages[0].timing_messages, 2);
  EXPECT_FALSE(FileExists(dir.File("out.lcm.timing.lcm")));
  EXPECT_FALSE(FileExists(dir.File("out.timing.lcm")));
}

TEST(ReplayTest, ATruncatedTailIsAWarningOrOnRequestAnError) {
  TempDir dir;
  WriteLog(dir.File("full.lcm"), LiveLikeLog());
  const std::string full = FileBytes(dir.File("full.lcm"));
  // The last event is "250 ODOM o3": 28 header bytes + 4 + 2. Cut 3 bytes off it.
  testing::WriteFileBytes(dir.File("cut.lcm"), full.substr(0, full.size() - 3));
  const ReplayFileResult r =
      ReplayLogFile(dir.File("cut.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_NE(r.warning.find("truncated final event at byte " + std::to_string(full.size() - 34)),
            std::string::npos)
      << r.warning;
  EXPECT_EQ(r.input.damage, LogDamage::kTruncatedTail);
  EXPECT_EQ(r.events_read, 8);
  EXPECT_EQ(ReadLog(dir.File("out.lcm")).size(), 10u);  // everything up to "212 TRUTH t2"

  ReplayFileOptions strict = Options(dir);
  strict.truncated_tail_is_error = true;
  const ReplayFileResult s =
      ReplayLogFile(dir.File("cut.lcm"), dir.File("strict.lcm"), FakeStack(), strict);
  EXPECT_NE(s.error.find("truncated final event"), std::string::npos) << s.error;
  EXPECT_FALSE(FileExists(dir.File("strict.lcm")));
  EXPECT_FALSE(FileExists(dir.File("strict.lcm.partial")));
}

TEST(ReplayTest, EveryTruncationPointIsHandled) {
  // Cut the log at every byte: never a crash, the complete events replayed, a clean report.
  TempDir dir;
  WriteLog(dir.File("full.lcm"), LiveLikeLog());
  const std::string full = FileBytes(dir.File("full.lcm"));
  for (size_t cut = 0; cut < full.size(); ++cut) {
    testing::WriteFileBytes(dir.File("cut.lcm"), full.substr(0, cut));
    ReplayFileOptions options;
    const ReplayFileResult r =
        ReplayLogFile(dir.File("cut.lcm"), dir.File("out.lcm"), FakeStack(), options);
    ASSERT_TRUE(r.error.empty()) << "cut at " << cut << ": " << r.error;
    EXPECT_EQ(r.events_read, r.input.complete_events) << "cut at " << cut;
    EXPECT_EQ(r.input.damage == LogDamage::kNone, r.input.valid_bytes == static_cast<int64_t>(cut))
        << "cut at " << cut;
    EXPECT_TRUE(FileExists(dir.File("out.lcm")));
  }
}

TEST(ReplayTest, ACorruptLogIsAnErrorAndLeavesNoOutput) {
  TempDir dir;
  WriteLog(dir.File("full.lcm"), LiveLikeLog());
  std::string bytes = FileBytes(dir.File("full.lcm"));
  // Event sizes: 28 + channel + data. Break the sync word of the fourth event.
  const size_t fourth = (28 + 4 + 2) + (28 + 4 + 3) + (28 + 4 + 4);
  bytes[fourth] = 0x00;
  testing::WriteFileBytes(dir.File("bad.lcm"), bytes);
  const ReplayFileResult r =
      ReplayLogFile(dir.File("bad.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  EXPECT_EQ(r.input.damage, LogDamage::kCorrupt);
  EXPECT_EQ(r.input.complete_events, 3);
  EXPECT_NE(r.error.find("corrupt event header at byte " + std::to_string(fourth)),
            std::string::npos)
      << r.error;
  EXPECT_EQ(r.error.find('\n'), std::string::npos);
  EXPECT_FALSE(FileExists(dir.File("out.lcm")));
  EXPECT_FALSE(FileExists(dir.File("out.lcm.partial")));
  EXPECT_FALSE(FileExists(dir.File("out.timing.lcm")));

  // Impossible lengths are corrupt too.
  bytes = FileBytes(dir.File("full.lcm"));
  bytes[fourth + 20] = static_cast<char>(0x7f);  // channel length of the fourth event
  testing::WriteFileBytes(dir.File("bad2.lcm"), bytes);
  const ReplayFileResult r2 =
      ReplayLogFile(dir.File("bad2.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  EXPECT_NE(r2.error.find("channel length"), std::string::npos) << r2.error;
  EXPECT_FALSE(FileExists(dir.File("out.lcm")));

  // A data length that runs past the end looks like a truncated tail, but more events follow:
  // that is corruption, not a logger stopped mid-write.
  bytes = FileBytes(dir.File("full.lcm"));
  bytes[fourth + 25] = static_cast<char>(0x7f);  // data length of the fourth event
  testing::WriteFileBytes(dir.File("bad3.lcm"), bytes);
  const ReplayFileResult r3 =
      ReplayLogFile(dir.File("bad3.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  EXPECT_EQ(r3.input.damage, LogDamage::kCorrupt);
  EXPECT_NE(r3.error.find("but an event follows at byte " + std::to_string(fourth + 28 + 5 + 2)),
            std::string::npos)
      << r3.error;
  EXPECT_FALSE(FileExists(dir.File("out.lcm")));
}

TEST(ReplayTest, AnEmptyOrForeignFile) {
  TempDir dir;
  testing::WriteFileBytes(dir.File("empty.lcm"), "");
  const ReplayFileResult empty =
      ReplayLogFile(dir.File("empty.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  EXPECT_TRUE(empty.error.empty());
  EXPECT_TRUE(ReadLog(dir.File("out.lcm")).empty());
  testing::WriteFileBytes(dir.File("text.lcm"), "this is not an LCM log at all\n");
  const ReplayFileResult text =
      ReplayLogFile(dir.File("text.lcm"), dir.File("out2.lcm"), FakeStack(), Options(dir));
  EXPECT_NE(text.error.find("corrupt event header at byte 0"), std::string::npos) << text.error;
  EXPECT_FALSE(FileExists(dir.File("out2.lcm")));
  EXPECT_THROW(ReplayLogFile(dir.File("missing.lcm"), dir.File("out3.lcm"), FakeStack(),
                             Options(dir)),
               std::runtime_error);
}

// Before: a directory replayed as an empty log (exit 0, empty output) and /dev/zero never ended
// (LCM's reader looks for a sync word forever; the probe was killed after 5 s).
TEST(ReplayTest, ALogThatIsNoFileIsAnErrorNamingIt) {
  TempDir dir;
  const std::string fifo = dir.File("fifo.lcm");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& input : {dir.path(), std::string("/dev/zero"), fifo}) {
    try {
      ReplayLogFile(input, dir.File("out.lcm"), FakeStack(), Options(dir));
      ADD_FAILURE() << input << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), input + ": not a log file (not a regular file)");
    }
    EXPECT_FALSE(FileExists(dir.File("out.lcm")));
    EXPECT_FALSE(FileExists(dir.File("out.timing.lcm")));
  }
}

TEST(ReplayTest, AStopRequestEndsTheReplayAndLeavesNoOutput) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  ReplayFileOptions options = Options(dir);
  int checks = 0;
  options.should_stop = [&] { return ++checks > 3; };
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), options);
  EXPECT_EQ(r.error, "stopped after 3 of 9 events");
  EXPECT_EQ(r.events_read, 3);
  EXPECT_FALSE(FileExists(dir.File("out.lcm")));
  EXPECT_FALSE(FileExists(dir.File("out.timing.lcm")));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().rfind("out", 0), std::string::npos)
        << entry.path();
  }
}

TEST(ReplayTest, AThrowingStageIsCountedAndTheReplayGoesOn) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"),
           {Event(1, "FEAT", "ok"), Event(2, "FEAT", "boom"), Event(3, "FEAT", "fine")});
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), Options(dir));
  ASSERT_TRUE(r.error.empty());
  EXPECT_EQ(r.stages[1].errors, 1);
  EXPECT_EQ(r.stages[1].messages_handled, 3);
  EXPECT_EQ(r.stages[1].messages_published, 2);
  EXPECT_EQ(ReadLog(dir.File("out.lcm")).size(), 5u);
}

// Publishes its declared FEAT and an undeclared EXTRA.
class UndeclaringSegmenter : public Stage {
 public:
  std::string Name() const override { return "undeclaring"; }
  std::vector<std::string> InputChannels() const override { return {"SCAN"}; }
  std::vector<std::string> OutputChannels() const override { return {"FEAT"}; }
  void Handle(const std::string&, const void*, int, MessageSink& out) override {
    out.Publish("FEAT", "f", 1);
    out.Publish("EXTRA", "e", 1);
  }
};

TEST(ReplayTest, AnUndeclaredOutputChannelIsAStageErrorAndIsDropped) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), {Event(1, "SCAN", "s"), Event(2, "EXTRA", "recorded")});
  std::vector<std::unique_ptr<Stage>> stages;
  stages.push_back(std::make_unique<UndeclaringSegmenter>());
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), std::move(stages), Options(dir));
  ASSERT_TRUE(r.error.empty());
  EXPECT_EQ(r.stages[0].errors, 1);
  EXPECT_EQ(r.stages[0].messages_published, 1);
  std::vector<std::string> lines;
  for (const LogEvent& e : ReadLog(dir.File("out.lcm"))) lines.push_back(e.channel + " " + Text(e));
  EXPECT_EQ(lines, (std::vector<std::string>{"SCAN s", "FEAT f", "EXTRA recorded"}));
}

TEST(ReplayTest, RefusesToOverwriteItsInput) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  const std::string before = FileBytes(dir.File("in.lcm"));
  EXPECT_THROW(ReplayLogFile(dir.File("in.lcm"), dir.File("in.lcm"), FakeStack(), Options(dir)),
               std::runtime_error);
  EXPECT_EQ(FileBytes(dir.File("in.lcm")), before);
}

TEST(ReplayTest, ReportsProgress) {
  TempDir dir;
  std::vector<LogEvent> events;
  for (int k = 0; k < 100; ++k) events.push_back(Event(k * 1000000LL, "ODOM", "o"));
  WriteLog(dir.File("in.lcm"), events);
  ReplayFileOptions options;
  options.progress_every_events = 30;
  options.progress_every_log_s = 1e9;
  std::vector<int64_t> reported;
  options.on_progress = [&](const ReplayProgress& p) {
    reported.push_back(p.events_done);
    EXPECT_EQ(p.events_total, 100);
    EXPECT_EQ(p.log_span_us, 99000000);
  };
  ASSERT_TRUE(ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), options)
                  .error.empty());
  EXPECT_EQ(reported, (std::vector<int64_t>{30, 60, 90}));
  // By log time: every 25 s of log.
  options.progress_every_events = 1000000;
  options.progress_every_log_s = 25.0;
  reported.clear();
  ASSERT_TRUE(ReplayLogFile(dir.File("in.lcm"), dir.File("out2.lcm"), FakeStack(), options)
                  .error.empty());
  EXPECT_EQ(reported, (std::vector<int64_t>{26, 51, 76}));
}

// A damaged or odd log may jump by centuries, or run backwards: progress stays one line per
// step reached, computed at once (stepping through a jump of 1e18 us would never end).
TEST(ReplayTest, ProgressSurvivesTimestampJumps) {
  TempDir dir;
  const int64_t far = std::numeric_limits<int64_t>::max() - 5;
  WriteLog(dir.File("in.lcm"), {Event(std::numeric_limits<int64_t>::min() + 3, "ODOM", "a"),
                                Event(0, "ODOM", "b"), Event(far, "ODOM", "c"),
                                Event(-7, "ODOM", "d"), Event(far, "ODOM", "e")});
  ReplayFileOptions options;
  options.progress_every_events = 1000;
  options.progress_every_log_s = 1e-12;  // below one microsecond: one microsecond
  std::vector<int64_t> reported;
  options.on_progress = [&](const ReplayProgress& p) { reported.push_back(p.events_done); };
  const ReplayFileResult r =
      ReplayLogFile(dir.File("in.lcm"), dir.File("out.lcm"), FakeStack(), options);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.events_written, 5);
  // Events 2 and 3 reach new steps (the saturated difference); 4 runs backwards; 5 repeats 3's
  // saturated time, which is the last step there is.
  EXPECT_EQ(reported, (std::vector<int64_t>{2, 3}));
}

TEST(ReplayConfigTest, ReadsTheReplaySection) {
  const std::vector<std::string> stack = {"segmenter", "estimator"};
  const ReplaySettings defaults = ReadReplaySettings(Config(), stack);
  EXPECT_EQ(defaults.stages, stack);
  EXPECT_EQ(defaults.file_options.progress_every_events, 20000);
  EXPECT_DOUBLE_EQ(defaults.file_options.progress_every_log_s, 30.0);
  EXPECT_FALSE(defaults.file_options.truncated_tail_is_error);
  const Config config = Config::FromString(
      "replay:\n  stages: [estimator]\n  progress_every_events: 5\n"
      "  progress_every_log_s: 2.5\n  truncated_tail: error\n",
      "stack.yaml");
  const ReplaySettings s = ReadReplaySettings(config.Child("replay"), stack);
  EXPECT_EQ(s.stages, std::vector<std::string>{"estimator"});
  EXPECT_EQ(s.file_options.progress_every_events, 5);
  EXPECT_DOUBLE_EQ(s.file_options.progress_every_log_s, 2.5);
  EXPECT_TRUE(s.file_options.truncated_tail_is_error);
}

// The schema names every setting once, the reader reads every one (set to their defaults they
// give the defaults), and docs/tools.md carries the generated table.
TEST(ReplayConfigTest, EverySettingIsReadAndDocumented) {
  const std::string table = ReplayOptionsTable();
  const std::vector<slammtt::testing::OptionsTableRow> rows =
      slammtt::testing::ParseOptionsTable(table);
  ASSERT_EQ(rows.size(), 3u) << table;
  const ReplaySettings s = ReadReplaySettings(
      Config::FromString(slammtt::testing::SectionOfDefaults("replay", rows), "every.yaml")
          .Child("replay"),
      {"estimator"});
  const ReplayFileOptions d;
  EXPECT_EQ(s.file_options.progress_every_events, d.progress_every_events);
  EXPECT_EQ(s.file_options.progress_every_log_s, d.progress_every_log_s);
  EXPECT_EQ(s.file_options.truncated_tail_is_error, d.truncated_tail_is_error);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/tools.md");
  ASSERT_FALSE(docs.empty()) << "docs/tools.md is part of the checkout";
  EXPECT_NE(docs.find(table), std::string::npos)
      << "docs/tools.md: replace the replay: table by `slammtt-replay --options-table`";
}

TEST(ReplayConfigTest, BadValuesNameTheKey) {
  for (const auto& [yaml, key] : std::vector<std::pair<std::string, std::string>>{
           {"replay:\n  stagse: [estimator]\n", "stagse"},
           {"replay:\n  progress_every_events: 0\n", "progress_every_events"},
           {"replay:\n  progress_every_log_s: 0\n", "progress_every_log_s"},
           {"replay:\n  progress_every_log_s: 1e-9\n", "progress_every_log_s"},
           {"replay:\n  progress_every_log_s: 1e300\n", "progress_every_log_s"},
           {"replay:\n  truncated_tail: maybe\n", "truncated_tail"}}) {
    try {
      ReadReplaySettings(Config::FromString(yaml, "stack.yaml").Child("replay"), {});
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("stack.yaml:2"), std::string::npos) << e.what();
    }
  }
}

TEST(ReplayTest, ScanCountsChannels) {
  TempDir dir;
  WriteLog(dir.File("in.lcm"), LiveLikeLog());
  const LogScan scan = ScanLogFile(dir.File("in.lcm"));
  EXPECT_EQ(scan.complete_events, 9);
  EXPECT_EQ(scan.channels.size(), 5u);
  EXPECT_EQ(scan.channels.at("ODOM").events, 3);
  EXPECT_EQ(scan.channels.at("SCAN").bytes, 5);
  EXPECT_EQ(scan.channels.at("TRUTH").first_timestamp_us, 112);
  EXPECT_EQ(scan.first_timestamp_us, 100);
  EXPECT_EQ(scan.last_timestamp_us, 250);
  EXPECT_EQ(scan.damage, LogDamage::kNone);
  EXPECT_EQ(scan.valid_bytes, scan.file_size);
}

}  // namespace
}  // namespace slammtt
