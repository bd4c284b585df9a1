// Damaged logs at random: whatever the bytes, replay never crashes, never leaves a partial
// output, and either succeeds on every complete event or reports one line. Short by default;
// SLAMMTT_LONG_TESTS=1 runs many more cases.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "tests/tools/log_test_util.h"
#include "tools/replay/log_replay.h"

namespace slammtt {
namespace {

class CopyStage : public Stage {
 public:
  std::string Name() const override { return "copy"; }
  std::vector<std::string> InputChannels() const override { return {"IN"}; }
  std::vector<std::string> OutputChannels() const override { return {"OUT"}; }
  void Handle(const std::string&, const void* data, int size, MessageSink& out) override {
    out.Publish("OUT", data, size);
  }
};

TEST(ReplayFuzzTest, RandomlyDamagedLogs) {
  const bool long_run = std::getenv("SLAMMTT_LONG_TESTS") != nullptr &&
                        std::string(std::getenv("SLAMMTT_LONG_TESTS")) == "1";
  const int cases = long_run ? 20000 : 300;
  testing::TempDir dir;
  std::vector<LogEvent> events;
  std::mt19937_64 rng(7);
  for (int k = 0; k < 40; ++k) {
    LogEvent e;
    e.timestamp_us = 1000 * k;
    e.channel = k % 2 == 0 ? "IN" : "OTHER_CHANNEL";
    e.data.resize(static_cast<size_t>(rng() % 64));
    for (uint8_t& b : e.data) b = static_cast<uint8_t>(rng());
    events.push_back(e);
  }
  testing::WriteLog(dir.File("good.lcm"), events);
  const std::string good = testing::FileBytes(dir.File("good.lcm"));
  for (int c = 0; c < cases; ++c) {
    std::string bytes = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] = static_cast<char>(rng());
    if (rng() % 3 == 0) bytes.resize(rng() % bytes.size());
    testing::WriteFileBytes(dir.File("bad.lcm"), bytes);
    std::vector<std::unique_ptr<Stage>> stages;
    stages.push_back(std::make_unique<CopyStage>());
    ReplayFileOptions options;
    options.timing_path = dir.File("out.timing.lcm");
    std::remove(dir.File("out.lcm").c_str());
    const ReplayFileResult r =
        ReplayLogFile(dir.File("bad.lcm"), dir.File("out.lcm"), std::move(stages), options);
    ASSERT_FALSE(testing::FileExists(dir.File("out.lcm.partial"))) << "case " << c;
    if (r.error.empty()) {
      ASSERT_TRUE(testing::FileExists(dir.File("out.lcm"))) << "case " << c;
      ASSERT_EQ(r.events_read, r.input.complete_events) << "case " << c;
      ASSERT_NE(r.input.damage, LogDamage::kCorrupt) << "case " << c;
    } else {
      ASSERT_FALSE(testing::FileExists(dir.File("out.lcm"))) << "case " << c;
      ASSERT_EQ(r.error.find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace slammtt
