// The large-loop family (config/scenarios/large-loop.yaml) through slammtt-world,
// slammtt-replay with estimator/config/large-loop.yaml (the estimator's local window of static
// landmarks and the smoother) and slammtt-eval: nothing of the map is lost and the loop closes
// (docs/smoother.md, "Large loop"). The default suite runs a small version (300 landmarks, seed
// 1, 30-60 s); the figures (1000 landmarks, seeds 1-10: smoothed ATE <= 0.2 m, static
// recall >= 0.95) are large_loop_targets_test (label target_open, docs/targets.md).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "runtime/lcm_io.h"
#include "slammtt_msgs/estimator_status_t.hpp"
#include "slammtt_msgs/map_t.hpp"
#include "slammtt_msgs/smoother_input_t.hpp"
#include "slammtt_msgs/stage_timing_t.hpp"
#include "tests/support/child_process.h"
#include "tests/tools/log_test_util.h"

namespace slammtt {
namespace {

using testing::Shell;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

// The shipped scenario with `count` landmarks.
std::string ScenarioWith(int count, const testing::TempDir& dir) {
  std::string text = testing::FileBytes(std::string(SLAMMTT_SOURCE_DIR) +
                                        "/config/scenarios/large-loop.yaml");
  text = std::regex_replace(text, std::regex("\n  count: [0-9]+\n"),
                            "\n  count: " + std::to_string(count) + "\n");
  const std::string path = dir.File("large-loop.yaml");
  testing::WriteFileBytes(path, text);
  return path;
}

std::string Config() {
  return std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/large-loop.yaml";
}

template <class Msg>
Msg DecodeOrFail(const LogEvent& e) {
  Msg m;
  EXPECT_TRUE(Decode(e.data.data(), static_cast<int>(e.data.size()), &m)) << e.channel;
  return m;
}

TEST(LargeLoopTest, NothingOfTheMapIsLostAndTheLoopCloses) {
  testing::TempDir dir;
  std::string out;
  ASSERT_EQ(Shell(Bin("slammtt-world") + " --quiet --scenario " + ScenarioWith(300, dir) +
                      " --seed 1 --log " + dir.File("world.lcm"),
                  &out),
            0)
      << out;
  ASSERT_EQ(Shell(Bin("slammtt-replay") + " --quiet " + dir.File("world.lcm") + " -o " +
                      dir.File("run.lcm") + " --config " + Config(),
                  &out),
            0)
      << out;

  // The landmarks that were ever in the filter's map are in its final map (the state's and the
  // archive's), but for the few the classifier took out of it (a static landmark whose
  // sightings say it moved becomes undecided again: 5 of 327 on this run, none by the window:
  // LandmarkWindowTest); SMOOTHER_INPUT sights landmarks of the first minute again in the last
  // 40 s, and the smoother still has them.
  std::set<int64_t> ever_mapped;
  slammtt_msgs::map_t final_map;
  slammtt_msgs::map_t final_smoothed_map;
  slammtt_msgs::estimator_status_t status;
  std::set<int64_t> seen_early;
  std::set<int64_t> seen_again;
  int64_t first_utime = -1;
  LogReader run(dir.File("run.lcm"));
  while (auto e = run.Next()) {
    if (first_utime < 0) first_utime = e->timestamp_us;
    const double t_s = 1e-6 * static_cast<double>(e->timestamp_us - first_utime);
    if (e->channel == "MAP") {
      final_map = DecodeOrFail<slammtt_msgs::map_t>(*e);
      for (const auto& l : final_map.landmarks) ever_mapped.insert(l.id);
    } else if (e->channel == "SMOOTHED_MAP") {
      final_smoothed_map = DecodeOrFail<slammtt_msgs::map_t>(*e);
    } else if (e->channel == "ESTIMATOR_STATUS") {
      status = DecodeOrFail<slammtt_msgs::estimator_status_t>(*e);
    } else if (e->channel == "SMOOTHER_INPUT") {
      const auto input = DecodeOrFail<slammtt_msgs::smoother_input_t>(*e);
      for (const auto& o : input.observations) {
        if (o.tentative) continue;
        if (t_s < 60.0) seen_early.insert(o.landmark_id);
        if (t_s > 360.0 && seen_early.count(o.landmark_id) > 0) seen_again.insert(o.landmark_id);
      }
    }
  }
  std::set<int64_t> final_ids;
  for (const auto& l : final_map.landmarks) final_ids.insert(l.id);
  EXPECT_EQ(final_ids.size(), final_map.landmarks.size()) << "an id twice in MAP";
  std::vector<int64_t> lost;
  std::set_difference(ever_mapped.begin(), ever_mapped.end(), final_ids.begin(), final_ids.end(),
                      std::back_inserter(lost));
  EXPECT_LE(lost.size(), ever_mapped.size() / 30)
      << lost.size() << " of " << ever_mapped.size() << " landmarks left the map";
  EXPECT_EQ(status.object_cap_hits, 0);
  EXPECT_GT(seen_again.size(), 10u) << seen_early.size() << " sighted in the first 60 s";
  std::set<int64_t> smoothed_ids;
  for (const auto& l : final_smoothed_map.landmarks) smoothed_ids.insert(l.id);
  for (const int64_t id : seen_again) EXPECT_EQ(smoothed_ids.count(id), 1u) << id;

  // The state stayed a window of the map: at most 150 objects while the archive held most.
  int64_t most_objects = 0;
  int64_t most_archived = 0;
  LogReader timing(dir.File("run.lcm.timing.lcm"));
  while (auto e = timing.Next()) {
    const auto t = DecodeOrFail<slammtt_msgs::stage_timing_t>(*e);
    if (t.stage != "estimator") continue;
    for (size_t i = 0; i < t.counter_name.size(); ++i) {
      if (t.counter_name[i] == "objects") most_objects = std::max(most_objects, t.counter_value[i]);
      if (t.counter_name[i] == "archived") {
        most_archived = std::max(most_archived, t.counter_value[i]);
      }
    }
  }
  EXPECT_LT(most_objects, 150);
  EXPECT_GT(most_archived, 150);

  // The map has about one landmark per post (none started twice in bulk), and the evaluation
  // finds most posts in the smoother's map (the filter's keeps the drift each landmark had when
  // it left the state: docs/smoother.md, "Large loop").
  ASSERT_EQ(Shell(Bin("slammtt-eval") + " --quiet " + dir.File("run.lcm") + " --config " +
                      Config() + " --json " + dir.File("report.json"),
                  &out),
            0)
      << out;
  const nlohmann::json report =
      nlohmann::json::parse(testing::FileBytes(dir.File("report.json")));
  const int64_t posts = report["detail"]["map"]["static_objects_ever_visible"].get<int64_t>();
  EXPECT_GE(posts, 290);
  EXPECT_LE(static_cast<int64_t>(final_map.landmarks.size()), posts + posts / 7);
  EXPECT_LE(static_cast<int64_t>(final_smoothed_map.landmarks.size()), posts + posts / 7);
  // 0.650 (filter 0.707) since re-entered landmarks wait until surely in range; 0.780 (filter
  // 0.523) before: the smoothed map's recall here follows its rotation about the first pose.
  EXPECT_GE(report["detail"]["smoothed_map"]["static_recall"].get<double>(), 0.6);
}

}  // namespace
}  // namespace slammtt
