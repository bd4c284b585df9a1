// Damaged scenario and trajectory files (label fuzz): every mutation of the shipped scenarios
// either loads or is refused with a ConfigError naming the file; whatever loads simulates one
// second without a crash, a hang or a non-finite number. The default run tries 300 mutations;
// SLAMMTT_LONG_TESTS=1 tries 10000. Deterministic (fixed seed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "tools/world/portable_random.h"
#include "tools/world/scenario_loader.h"
#include "tools/world/world_simulator.h"

namespace slammtt {
namespace {

int Mutations() {
  const char* long_tests = std::getenv("SLAMMTT_LONG_TESTS");
  return long_tests != nullptr && std::string(long_tests) == "1" ? 10000 : 300;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One random damage: a token replaced, a character deleted or inserted, a line duplicated,
// deleted or swapped with the next.
std::string Mutate(const std::string& text, std::mt19937_64& rng) {
  static const std::vector<std::string> tokens = {
      "-1", "0", "1e400", "-1e300", "nan", ".inf", "abc", "[]", "{}", "[1, 2, 3, 4, 5]", "~",
      "1e-300", "999999999999", "true", "\"\"", "{a: 1}", "- x", ":", "180", "0.0001"};
  std::string out = text;
  const size_t pos = static_cast<size_t>(UniformUnit(rng) * static_cast<double>(out.size()));
  const int kind = static_cast<int>(UniformUnit(rng) * 6.0);
  if (kind == 0) {  // replace the number or word at pos by a token
    auto in_token = [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-';
    };
    size_t begin = pos;
    while (begin > 0 && in_token(out[begin - 1])) --begin;
    size_t end = pos;
    while (end < out.size() && in_token(out[end])) ++end;
    out.replace(begin, end - begin, tokens[static_cast<size_t>(UniformUnit(rng) * tokens.size())]);
  } else if (kind == 1 && !out.empty()) {
    out.erase(pos, 1);
  } else if (kind == 2) {
    out.insert(pos, 1, "[]{},:-# \n"[static_cast<size_t>(UniformUnit(rng) * 10.0)]);
  } else {
    std::vector<std::string> lines;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    if (lines.size() < 2) return out;
    const size_t i = static_cast<size_t>(UniformUnit(rng) * static_cast<double>(lines.size() - 1));
    if (kind == 3) lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
    if (kind == 4) lines.erase(lines.begin() + static_cast<long>(i));
    if (kind == 5) std::swap(lines[i], lines[i + 1]);
    out.clear();
    for (const std::string& line : lines) out += line + "\n";
  }
  return out;
}

bool Finite(const Pose2D& p) {
  return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.heading_rad);
}

TEST(ScenarioFuzzTest, DamagedScenariosLoadOrFailCleanlyAndSimulate) {
  const std::string dir = std::string(SLAMMTT_SOURCE_DIR) + "/config/scenarios";
  const std::vector<std::string> names = {"s1-crossing", "s2-lobby", "s3-no-static", "rplidar-a2",
                                          "crowd-zara02", "office", "corridor"};
  std::vector<std::string> texts;
  for (const std::string& name : names) texts.push_back(ReadText(dir + "/" + name + ".yaml"));
  std::mt19937_64 rng(20180101);
  int loaded = 0;
  int refused = 0;
  const int n = Mutations();
  for (int i = 0; i < n; ++i) {
    const size_t which = static_cast<size_t>(i) % texts.size();
    std::string text = Mutate(texts[which], rng);
    if (UniformUnit(rng) < 0.3) text = Mutate(text, rng);
    const std::string source = "mutant-" + std::to_string(i) + ".yaml";
    Scenario scenario;
    try {
      scenario = LoadScenarioFromString(text, source, dir);
    } catch (const ConfigError& e) {
      ++refused;
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_TRUE(what.rfind(source + ":", 0) == 0 || what.rfind(source + ": ", 0) == 0) << what;
      continue;
    }
    ++loaded;
    scenario.duration_s = std::min(scenario.duration_s, 1.0);
    WorldSimulator world(scenario, static_cast<uint64_t>(i), SensorOutput::kBoth);
    int events = 0;
    while (!world.Done() && events < 100000) {
      const WorldEvent e = world.Next();
      ++events;
      if (e.kind == WorldEvent::Kind::kOdometry) {
        ASSERT_TRUE(Finite(e.odometry.pose)) << source << "\n" << text;
        continue;
      }
      ASSERT_TRUE(Finite(e.sensor.truth.robot.pose)) << source;
      for (const SimulatedBeam& b : e.sensor.scan) ASSERT_TRUE(std::isfinite(b.range_m)) << source;
      for (const PointFeature& f : e.sensor.features) {
        ASSERT_TRUE(std::isfinite(f.range_m) && std::isfinite(f.bearing_rad)) << source;
      }
      for (const ObjectTruth& o : e.sensor.truth.objects) {
        ASSERT_TRUE(std::isfinite(o.x_m) && std::isfinite(o.y_m) && std::isfinite(o.vx_mps))
            << source;
      }
    }
    EXPECT_TRUE(world.Done()) << source;
  }
  // Both outcomes happen (the mutations are neither all harmless nor all fatal).
  EXPECT_GT(loaded, n / 20);
  EXPECT_GT(refused, n / 5);
  std::printf("%d mutations: %d loaded and simulated, %d refused\n", n, loaded, refused);
}

TEST(ScenarioFuzzTest, DamagedTrajectoryFilesFailWithTheirLine) {
  const std::string original =
      ReadText(std::string(SLAMMTT_SOURCE_DIR) + "/data/pedestrians/zara02.tsv").substr(0, 4000);
  const std::string path = ::testing::TempDir() + "fuzz_" + std::to_string(::getpid()) + ".tsv";
  std::mt19937_64 rng(7);
  const int n = Mutations() / 3;
  int refused = 0;
  for (int i = 0; i < n; ++i) {
    std::ofstream(path) << Mutate(original, rng);
    try {
      for (const RecordedTrack& track : ReadRecordedTracks(path)) {
        for (size_t k = 1; k < track.points.size(); ++k) {
          ASSERT_GT(track.points[k].t_s, track.points[k - 1].t_s);
        }
      }
    } catch (const ConfigError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
    }
  }
  std::remove(path.c_str());
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace slammtt
