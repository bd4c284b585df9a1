// Damaged messages at random in an evaluation log: slammtt-eval's reading and scoring never
// throw, never produce NaN, and count what they reject. Short by default; SLAMMTT_LONG_TESTS=1
// runs many more cases.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "tests/tools/hand_built_log.h"
#include "tests/tools/log_test_util.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/eval/report_json.h"
#include "tools/plots/eval_plots.h"

namespace slammtt {
namespace {

TEST(EvalFuzzTest, RandomlyDamagedMessages) {
  const char* long_env = std::getenv("SLAMMTT_LONG_TESTS");
  const bool long_run = long_env != nullptr && std::string(long_env) == "1";
  const int cases = long_run ? 5000 : 150;
  testing::TempDir dir;
  testing::WriteHandBuiltLog(dir.File("good.lcm"), true);
  const std::vector<LogEvent> good = testing::ReadLog(dir.File("good.lcm"));
  std::mt19937_64 rng(11);
  int64_t rejected_total = 0;
  for (int c = 0; c < cases; ++c) {
    std::vector<LogEvent> events = good;
    const int damaged = 1 + static_cast<int>(rng() % 4);
    for (int d = 0; d < damaged; ++d) {
      LogEvent& e = events[rng() % events.size()];
      if (e.data.empty()) continue;
      switch (rng() % 3) {
        case 0:  // flip bytes
          for (int k = 0; k < 3; ++k) e.data[rng() % e.data.size()] = static_cast<uint8_t>(rng());
          break;
        case 1:  // truncate the message
          e.data.resize(rng() % e.data.size());
          break;
        default:  // an extreme double somewhere past the fingerprint
          if (e.data.size() > 24) {
            const size_t at = 16 + 8 * (rng() % ((e.data.size() - 16) / 8));
            const uint64_t patterns[] = {0x7ff0000000000000ULL, 0x7ff8000000000000ULL,
                                         0x7fefffffffffffffULL, 0xffefffffffffffffULL};
            const uint64_t bits = patterns[rng() % 4];
            for (int k = 0; k < 8 && at + k < e.data.size(); ++k) {
              e.data[at + k] = static_cast<uint8_t>(bits >> (56 - 8 * k));
            }
          }
      }
    }
    testing::WriteLog(dir.File("bad.lcm"), events);
    LogReadResult read;
    EvalInput input;
    ASSERT_NO_THROW(input = ReadEvalInput(dir.File("bad.lcm"), Channels(), &read)) << c;
    EvaluationReport report;
    ASSERT_NO_THROW(report = Evaluate(input, EvalOptions())) << c;
    std::string json;
    ASSERT_NO_THROW(json = ReportToJson(input, report).dump()) << c;
    ASSERT_EQ(json.find("NaN"), std::string::npos) << c;
    ASSERT_EQ(json.find("nan"), std::string::npos) << c;
    ASSERT_NO_THROW(TracksSvg(report)) << c;
    ASSERT_NO_THROW(MapSvg(report)) << c;
    ASSERT_EQ(ErrorsSvg(report).find("nan"), std::string::npos) << c;
    for (const auto& [key, n] : input.rejected) rejected_total += n;
  }
  EXPECT_GT(rejected_total, 0);  // the damage was seen, not silently used
}

}  // namespace
}  // namespace slammtt
