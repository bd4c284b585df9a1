#include "tools/timing/timing_table.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "slammtt_msgs/stage_timing_t.hpp"
#include "tests/tools/log_test_util.h"
#include "tools/timing/timing_log.h"
#include "tools/timing/timing_report.h"

namespace slammtt {
namespace {

using testing::RunCommand;

// slammtt-timing --json on `log`, stderr into `err_path`; the parsed JSON (exit status 0 asserted).
nlohmann::json TimingProgramJson(const std::string& log, const std::string& err_path) {
  int status = 0;
  const std::string out = RunCommand(
      std::string(SLAMMTT_BIN_DIR) + "/slammtt-timing --json " + log + " 2>" + err_path, &status);
  EXPECT_EQ(status, 0) << out;
  return status == 0 ? nlohmann::json::parse(out) : nlohmann::json();
}

TEST(TimingTableTest, NearestRankPercentiles) {
  std::vector<int64_t> values;
  for (int64_t v = 100; v >= 1; --v) values.push_back(v);  // any order
  const DurationStats s = ComputeStats(values);
  EXPECT_EQ(s.count, 100);
  EXPECT_EQ(s.median, 50);
  EXPECT_EQ(s.p95, 95);
  EXPECT_EQ(s.p99, 99);
  EXPECT_EQ(s.max, 100);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);

  const DurationStats four = ComputeStats({4, 1, 3, 2});
  EXPECT_EQ(four.median, 2);  // the lower middle value: always a measured one
  EXPECT_EQ(four.p95, 4);
  const DurationStats one = ComputeStats({7});
  EXPECT_EQ(one.median, 7);
  EXPECT_EQ(one.p99, 7);
  const DurationStats none = ComputeStats({});
  EXPECT_EQ(none.count, 0);
  EXPECT_EQ(none.max, 0);
}

TEST(TimingTableTest, SummarisesStagesSubstagesAndPeriod) {
  std::vector<TimingRecord> records;
  for (int k = 0; k < 10; ++k) {
    // The segmenter at 10 Hz taking 1..10 ms, the estimator at 10 Hz taking 20 ms.
    records.push_back({k * 100000, "segmenter", (k + 1) * 1000000, {{"split", (k + 1) * 1000}},
                       {{"beams", 360}}});
    records.push_back({k * 100000, "estimator", 20000000,
                       {{"predict", 1000}, {"gating", 2000}, {"ransac", 15000}}, {}});
  }
  const std::vector<StageTimingSummary> s = SummariseTiming(records);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].stage, "segmenter");
  EXPECT_EQ(s[0].total_ns.median, 5000000);
  EXPECT_EQ(s[0].total_ns.max, 10000000);
  ASSERT_TRUE(s[0].period_median_us.has_value());
  EXPECT_EQ(*s[0].period_median_us, 100000);
  EXPECT_DOUBLE_EQ(*s[0].share_of_period, 0.05);  // 5 ms of 100 ms
  // Load: 55 ms of work over the 0.9 s the records span.
  EXPECT_DOUBLE_EQ(*s[0].load, 55e6 / 0.9e9);
  ASSERT_EQ(s[0].counters.size(), 1u);
  EXPECT_EQ(s[0].counters[0].stats.median, 360);
  ASSERT_EQ(s[1].substages_ns.size(), 3u);
  EXPECT_EQ(s[1].substages_ns[0].name, "predict");
  EXPECT_EQ(s[1].substages_ns[2].name, "ransac");
  EXPECT_EQ(s[1].substages_ns[2].stats.p99, 15000);
  EXPECT_DOUBLE_EQ(*s[1].share_of_period, 0.2);
}

TEST(TimingTableTest, ASingleRecordHasNoPeriod) {
  const std::vector<StageTimingSummary> s = SummariseTiming({{5, "x", 10, {}, {}}});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FALSE(s[0].period_median_us.has_value());
  EXPECT_FALSE(s[0].share_of_period.has_value());
  EXPECT_TRUE(SummariseTiming({}).empty());
}

TEST(TimingReportTest, TableRowsAreMicrosecondsWithShareAndCounts) {
  std::vector<TimingRecord> records;
  for (int k = 0; k < 4; ++k) {
    records.push_back({k * 125000, "segmenter", 1000 * (k + 1), {{"sort", 500}}, {{"beams", 360}}});
  }
  const std::string table = TimingTableText(SummariseTiming(records));
  // Median 2.0 us (nearest rank: the lower middle), p95 = p99 = max = 4.0 us; 2 us of 125 ms is
  // 0.0016 %; load 10 us over 0.375 s = 0.0027 %.
  EXPECT_NE(table.find("segmenter                         4        2.0        4.0        4.0 "
                       "       4.0   0.002% of the 125.0 ms period, load 0.003%\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("\n  sort                            4        0.5        0.5        0.5 "
                       "       0.5\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("  #beams                          4        360        360        360 "
                       "       360   (count)\n"),
            std::string::npos)
      << table;
}

TEST(TimingReportTest, JsonHasNullWhereThereIsNoPeriod) {
  const nlohmann::json j =
      TimingJson(SummariseTiming({{5, "x", 10, {{"a", 4}}, {}}}), "t.lcm", "STAGE_TIMING", 1, 2);
  EXPECT_EQ(j["log"], "t.lcm");
  EXPECT_EQ(j["messages"], 1);
  EXPECT_EQ(j["skipped_messages"], 2);
  ASSERT_EQ(j["stages"].size(), 1u);
  EXPECT_EQ(j["stages"][0]["total_ns"]["median"], 10);
  EXPECT_EQ(j["stages"][0]["substages"][0]["ns"]["max"], 4);
  EXPECT_TRUE(j["stages"][0]["period_median_us"].is_null());
  EXPECT_TRUE(j["stages"][0]["share_of_period"].is_null());
  EXPECT_TRUE(j["stages"][0]["load"].is_null());
}

// Before: one STAGE_TIMING with a non-UTF-8 byte in its stage name made slammtt-timing --json
// fail ("[json.exception.type_error.316] invalid UTF-8 byte at index 3: 0xFF", exit 1).
TEST(TimingReportTest, JsonTextSurvivesANameThatIsNoUtf8) {
  const std::string name = "bad\xff\xfename";
  const std::string text = TimingJsonText(
      TimingJson(SummariseTiming({{5, name, 10, {{name, 4}}, {}}}), "t\xff.lcm", "STAGE_TIMING",
                 1, 0));
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["stages"][0]["stage"], "bad\xEF\xBF\xBD\xEF\xBF\xBDname");  // U+FFFD each
  EXPECT_EQ(j["stages"][0]["substages"][0]["name"], j["stages"][0]["stage"]);
  EXPECT_EQ(text.back(), '\n');
}

// Before: 10 records of total_ns = INT64_MAX gave a load of -8.9e-09 and a mean of -1 (the sum
// overflowed); durations beyond an hour are no measurement and are now skipped and counted.
TEST(TimingTableTest, HugeDurationsNeverOverflowTheSums) {
  const int64_t huge = std::numeric_limits<int64_t>::max() / 4;
  const DurationStats stats = ComputeStats({huge, huge, huge, huge, huge, huge});
  EXPECT_EQ(stats.sum, std::numeric_limits<int64_t>::max());  // saturated
  EXPECT_DOUBLE_EQ(stats.mean, static_cast<double>(huge));
  std::vector<TimingRecord> records;
  for (int k = 0; k < 10; ++k) records.push_back({1000000 + 125000 * k, "estimator", huge, {}, {}});
  const StageTimingSummary summary = SummariseTiming(records)[0];
  ASSERT_TRUE(summary.load.has_value());
  EXPECT_GT(*summary.load, 0.0);
}

TEST(TimingLogTest, DurationsBeyondAnHourAreSkippedAndCounted) {
  testing::TempDir dir;
  LogWriter writer(dir.File("timing.lcm"));
  for (int k = 0; k < 10; ++k) {
    slammtt_msgs::stage_timing_t msg{};
    msg.utime = 1000000 + 125000 * k;
    msg.stage = "estimator";
    msg.total_ns = k < 7 ? 100000 : std::numeric_limits<int64_t>::max();
    writer.WriteMessage(msg.utime, "STAGE_TIMING", msg);
  }
  slammtt_msgs::stage_timing_t sub{};
  sub.utime = 3000000;
  sub.stage = "estimator";
  sub.total_ns = 1000;
  sub.num_substages = 1;
  sub.substage = {"ransac"};
  sub.substage_ns = {int64_t{3600} * 1000000000 + 1};
  writer.WriteMessage(sub.utime, "STAGE_TIMING", sub);
  writer.Commit();
  const TimingLog log = ReadTimingLog(dir.File("timing.lcm"), "STAGE_TIMING");
  EXPECT_EQ(log.records.size(), 7u);
  EXPECT_EQ(log.implausible, 4);
  const nlohmann::json j = TimingProgramJson(dir.File("timing.lcm"), dir.File("err.txt"));
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["messages"], 7);
  EXPECT_EQ(j["skipped_messages"], 4);
  EXPECT_GT(j["stages"][0]["load"].get<double>(), 0.0);
  EXPECT_NE(testing::FileBytes(dir.File("err.txt")).find("skipped 4 STAGE_TIMING messages with "
                                                         "a duration beyond an hour"),
            std::string::npos)
      << testing::FileBytes(dir.File("err.txt"));
}

// The probe through the program: one STAGE_TIMING whose stage, sub-stage and counter
// names hold bytes that are no UTF-8, among good ones. Before: exit 1 and no JSON.
TEST(TimingProgramTest, JsonOfANameThatIsNoUtf8) {
  testing::TempDir dir;
  LogWriter writer(dir.File("timing.lcm"));
  for (int k = 0; k < 5; ++k) {
    slammtt_msgs::stage_timing_t msg{};
    msg.utime = 1000000 + k * 125000;
    msg.stage = k == 2 ? "seg\xffmenter" : "segmenter";
    msg.total_ns = 1000;
    msg.num_substages = 1;
    msg.substage = {k == 2 ? "so\xc3rt" : "sort"};
    msg.substage_ns = {300};
    msg.num_counters = 1;
    msg.counter_name = {k == 2 ? "\x80" "beams" : "beams"};
    msg.counter_value = {400};
    writer.WriteMessage(msg.utime, "STAGE_TIMING", msg);
  }
  writer.Commit();
  const nlohmann::json j = TimingProgramJson(dir.File("timing.lcm"), dir.File("err.txt"));
  ASSERT_FALSE(j.is_null()) << testing::FileBytes(dir.File("err.txt"));
  EXPECT_EQ(j["messages"], 5);
  ASSERT_EQ(j["stages"].size(), 2u);
  std::vector<std::string> stages;
  for (const auto& stage : j["stages"]) stages.push_back(stage["stage"]);
  std::sort(stages.begin(), stages.end());
  EXPECT_EQ(stages, (std::vector<std::string>{"segmenter", "seg\xEF\xBF\xBDmenter"}));
  const std::string text = j.dump();
  EXPECT_NE(text.find("so\xEF\xBF\xBDrt"), std::string::npos) << text;
  EXPECT_NE(text.find("\xEF\xBF\xBD" "beams"), std::string::npos) << text;
}

TEST(TimingLogTest, SkipsAndCountsBadMessages) {
  testing::TempDir dir;
  LogWriter writer(dir.File("timing.lcm"));
  slammtt_msgs::stage_timing_t good;
  good.utime = 7;
  good.stage = "segmenter";
  good.total_ns = 900;
  good.num_substages = 1;
  good.substage = {"sort"};
  good.substage_ns = {300};
  good.num_counters = 1;
  good.counter_name = {"beams"};
  good.counter_value = {400};
  writer.WriteMessage(1, "STAGE_TIMING", good);
  slammtt_msgs::stage_timing_t negative = good;
  negative.substage_ns = {-1};
  writer.WriteMessage(2, "STAGE_TIMING", negative);
  writer.WriteMessage(3, "OTHER_TIMING", good);  // another channel: not read
  const std::string junk = "garbage";
  writer.Write(4, "STAGE_TIMING", junk.data(), static_cast<int>(junk.size()));
  writer.Commit();
  const TimingLog log = ReadTimingLog(dir.File("timing.lcm"), "STAGE_TIMING");
  ASSERT_EQ(log.records.size(), 1u);
  EXPECT_EQ(log.records[0].utime, 7);
  EXPECT_EQ(log.records[0].stage, "segmenter");
  EXPECT_EQ(log.records[0].substages_ns,
            (std::vector<std::pair<std::string, int64_t>>{{"sort", 300}}));
  EXPECT_EQ(log.records[0].counters,
            (std::vector<std::pair<std::string, int64_t>>{{"beams", 400}}));
  EXPECT_EQ(log.negative, 1);
  EXPECT_EQ(log.undecodable, 1);
  EXPECT_TRUE(log.read.problem.empty());
}

TEST(TimingProgramTest, PrintsJsonFromATimingLog) {
  testing::TempDir dir;
  LogWriter writer(dir.File("timing.lcm"));
  for (int k = 0; k < 20; ++k) {
    slammtt_msgs::stage_timing_t msg;
    msg.utime = 1000000 + k * 125000;
    msg.stage = "estimator";
    msg.total_ns = 1000 * (k + 1);
    msg.num_substages = 2;
    msg.substage = {"predict", "ransac"};
    msg.substage_ns = {100, 900 * (k + 1)};
    msg.num_counters = 1;
    msg.counter_name = {"hypotheses"};
    msg.counter_value = {k};
    writer.WriteMessage(msg.utime, "STAGE_TIMING", msg);
  }
  const std::string junk = "not a timing message";
  writer.Write(5000000, "STAGE_TIMING", junk.data(), static_cast<int>(junk.size()));
  writer.Write(5000001, "OTHER", junk.data(), static_cast<int>(junk.size()));
  writer.Commit();

  const nlohmann::json j = TimingProgramJson(dir.File("timing.lcm"), dir.File("err.txt"));
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["messages"], 20);
  EXPECT_EQ(j["skipped_messages"], 1);
  ASSERT_EQ(j["stages"].size(), 1u);
  const nlohmann::json& e = j["stages"][0];
  EXPECT_EQ(e["stage"], "estimator");
  EXPECT_EQ(e["total_ns"]["median"], 10000);
  EXPECT_EQ(e["total_ns"]["p95"], 19000);
  EXPECT_EQ(e["total_ns"]["max"], 20000);
  EXPECT_EQ(e["period_median_us"], 125000);
  EXPECT_DOUBLE_EQ(e["share_of_period"].get<double>(), 10000.0 / 125e6);
  EXPECT_EQ(e["substages"][1]["name"], "ransac");
  EXPECT_EQ(e["substages"][1]["ns"]["p99"], 18000);
  EXPECT_EQ(e["counters"][0]["value"]["max"], 19);
  EXPECT_NE(testing::FileBytes(dir.File("err.txt")).find("skipped 1 undecodable"),
            std::string::npos);

  // The text table names every sub-stage.
  int status = 0;
  const std::string table =
      RunCommand(std::string(SLAMMTT_BIN_DIR) + "/slammtt-timing " + dir.File("timing.lcm") +
                     " 2>/dev/null",
                 &status);
  ASSERT_EQ(status, 0);
  EXPECT_NE(table.find("estimator"), std::string::npos);
  EXPECT_NE(table.find("  ransac"), std::string::npos);
  EXPECT_NE(table.find("of the 125.0 ms period"), std::string::npos) << table;
}

TEST(TimingProgramTest, ACorruptLogIsAnError) {
  testing::TempDir dir;
  testing::WriteFileBytes(dir.File("bad.lcm"), "garbage that is not a log");
  int status = 0;
  RunCommand(std::string(SLAMMTT_BIN_DIR) + "/slammtt-timing " + dir.File("bad.lcm") +
                 " >/dev/null 2>" + dir.File("err.txt"),
             &status);
  EXPECT_NE(status, 0);
  const std::string err = testing::FileBytes(dir.File("err.txt"));
  EXPECT_NE(err.find("corrupt event header at byte 0"), std::string::npos) << err;
}

}  // namespace
}  // namespace slammtt
