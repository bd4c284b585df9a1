// slammtt-world as a program: byte-identical logs for a seed, the channel contract of the log
// (channels, order, utime = event timestamp, sequence numbers), the options, and bad scenarios
// rejected with one line naming file, line and key, leaving no log and no partial file.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <filesystem>
#include <thread>
#include <fstream>
#include <map>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/features_t.hpp"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_geometry_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

namespace fs = std::filesystem;
using testing::ProcessResult;
using testing::ReadWholeFile;
using testing::RunProcess;

const std::string kWorld = std::string(SLAMMTT_BIN_DIR) + "/slammtt-world";
constexpr int64_t kEpoch = 1700000000000000;

class WorldCliTest : public ::testing::Test {
 protected:
  ProcessResult World(std::vector<std::string> args) {
    args.insert(args.begin(), kWorld);
    return RunProcess(args, dir_.string());
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return Path(name);
  }
  // Files left in the scratch folder other than the captured output.
  std::vector<std::string> LeftFiles() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (n != "stdout.txt" && n != "stderr.txt" && n.find(".yaml") == std::string::npos &&
          n.find(".tsv") == std::string::npos) {
        names.push_back(n);
      }
    }
    return names;
  }

  testing::TempDir temp_{"slammtt-world-cli"};  // removed with its content after the test
  const fs::path dir_ = temp_.path();
};

TEST_F(WorldCliTest, SameSeedGivesIdenticalBytesAndAnotherSeedDoesNot) {
  for (const std::string output : {"features", "scans"}) {
    SCOPED_TRACE(output);
    auto run = [&](const std::string& seed, const std::string& log) {
      return World({"--scenario", "s1-crossing", "--seed", seed, "--output", output, "--log",
                    Path(log)})
          .exit_code;
    };
    ASSERT_EQ(run("7", "a.lcm"), 0);
    ASSERT_EQ(run("7", "b.lcm"), 0);
    ASSERT_EQ(run("8", "c.lcm"), 0);
    const std::string a = ReadWholeFile(Path("a.lcm"));
    EXPECT_GT(a.size(), 100000u);
    EXPECT_TRUE(a == ReadWholeFile(Path("b.lcm")));
    const std::string c = ReadWholeFile(Path("c.lcm"));
    EXPECT_EQ(a.size(), c.size());  // same messages, other noise
    EXPECT_FALSE(a == c);
  }
}

TEST_F(WorldCliTest, OfficeWithLegsAndArtefactsIsByteIdenticalForASeed) {
  auto run = [&](const std::string& seed, const std::string& log) {
    return World({"--scenario", "office", "--seed", seed, "--output", "both", "--duration", "20",
                  "--log", Path(log)})
        .exit_code;
  };
  ASSERT_EQ(run("3", "a.lcm"), 0);
  ASSERT_EQ(run("3", "b.lcm"), 0);
  ASSERT_EQ(run("4", "c.lcm"), 0);
  const std::string a = ReadWholeFile(Path("a.lcm"));
  EXPECT_GT(a.size(), 1000000u);
  EXPECT_TRUE(a == ReadWholeFile(Path("b.lcm")));
  EXPECT_FALSE(a == ReadWholeFile(Path("c.lcm")));
}

TEST_F(WorldCliTest, S1LogFollowsTheChannelContract) {
  const ProcessResult run =
      World({"--scenario", "s1-crossing", "--seed", "7", "--log", Path("s1.lcm")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // One summary line.
  EXPECT_NE(run.err.find("slammtt-world: info: s1-crossing seed 7: 4444 messages (FEATURES 961, "
                         "GROUND_TRUTH 961, LASER_GEOMETRY 121, ODOMETRY 2401) for 120.00 s "
                         "simulated in "),
            std::string::npos)
      << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1);
  EXPECT_TRUE(LeftFiles() == std::vector<std::string>{"s1.lcm"});

  LogReader log(Path("s1.lcm"));
  std::map<std::string, int64_t> count;
  std::map<std::string, int64_t> next_sequence;
  int64_t last_utime = 0;
  std::string last_channel;
  const std::map<std::string, int> rank = {
      {"ODOMETRY", 0}, {"LASER_GEOMETRY", 1}, {"GROUND_TRUTH", 2}, {"FEATURES", 4}};
  int64_t frames = 0;  // sensor frames so far (GROUND_TRUTH messages)
  while (const std::optional<LogEvent> event = log.Next()) {
    ASSERT_EQ(rank.count(event->channel), 1u) << event->channel;
    int64_t utime = 0;
    int64_t sequence = -1;
    const int size = static_cast<int>(event->data.size());
    if (event->channel == "ODOMETRY") {
      slammtt_msgs::odometry_t m{};
      ASSERT_TRUE(Decode(event->data.data(), size, &m));
      utime = m.utime;
      sequence = m.sequence;
      if (count[event->channel] == 0) {
        EXPECT_EQ(m.x_m, 0.0);
        EXPECT_EQ(m.heading_rad, 0.0);
      }
    } else if (event->channel == "LASER_GEOMETRY") {
      // The scenario's laser (paper section 5.1), with the first frame and every 8th (8 Hz).
      slammtt_msgs::laser_geometry_t m{};
      ASSERT_TRUE(Decode(event->data.data(), size, &m));
      utime = m.utime;
      EXPECT_EQ(frames % 8, 0);
      EXPECT_EQ(m.mount_forward_m, 0.1);
      EXPECT_EQ(m.mount_left_m, 0.0);
      EXPECT_EQ(m.mount_yaw_rad, 0.0);
      EXPECT_EQ(m.view_start_rad, -0.5 * M_PI);
      EXPECT_EQ(m.view_end_rad, 0.5 * M_PI);
      EXPECT_EQ(m.range_min_m, 0.1);
      EXPECT_EQ(m.range_max_m, 30.0);
      EXPECT_EQ(m.source, "slammtt-world, scenario s1-crossing");
    } else if (event->channel == "GROUND_TRUTH") {
      slammtt_msgs::ground_truth_t m{};
      ASSERT_TRUE(Decode(event->data.data(), size, &m));
      utime = m.utime;
      ++frames;
      ASSERT_EQ(m.num_objects, 69 + 5);
      int moving = 0;
      int statics_visible = 0;
      for (const auto& o : m.objects) {
        const bool is_moving = o.object_class == slammtt_msgs::object_truth_t::CLASS_MOVING;
        moving += is_moving;
        statics_visible += !is_moving && o.visible;
        EXPECT_EQ(is_moving, o.id > 100);
      }
      EXPECT_EQ(moving, 5);
      EXPECT_GE(statics_visible, 3);
    } else {
      slammtt_msgs::features_t m{};
      ASSERT_TRUE(Decode(event->data.data(), size, &m));
      utime = m.utime;
      sequence = m.sequence;
      ASSERT_EQ(m.num_features, static_cast<int32_t>(m.features.size()));
      for (const auto& f : m.features) {
        EXPECT_EQ(f.num_points, 0);
        EXPECT_DOUBLE_EQ(f.range_var_m2, 0.04);
        EXPECT_GT(f.width_m, 0.0);
        EXPECT_LE(std::abs(f.bearing_rad), M_PI);
      }
    }
    EXPECT_EQ(event->timestamp_us, utime);  // log timestamp = message time
    if (last_channel.empty()) {
      EXPECT_EQ(event->channel, "ODOMETRY");
      EXPECT_EQ(utime, kEpoch);
    }
    EXPECT_GE(utime, last_utime);
    if (utime == last_utime && !last_channel.empty()) {
      EXPECT_LT(rank.at(last_channel), rank.at(event->channel)) << utime;
    }
    if (sequence >= 0) {
      EXPECT_EQ(sequence, next_sequence[event->channel]) << event->channel;
      next_sequence[event->channel] = sequence + 1;
    }
    last_utime = utime;
    last_channel = event->channel;
    ++count[event->channel];
  }
  EXPECT_EQ(count["ODOMETRY"], 2401);
  EXPECT_EQ(count["GROUND_TRUTH"], 961);
  EXPECT_EQ(count["LASER_GEOMETRY"], 121);
  EXPECT_EQ(count["FEATURES"], 961);
  EXPECT_EQ(last_utime, kEpoch + 120000000);
}

TEST_F(WorldCliTest, ScansBothOutputsDurationAndChannelNames) {
  const ProcessResult run =
      World({"--scenario", "rplidar-a2", "--output", "both", "--duration", "2", "--channel",
             "laser_scan=SIM_SCAN", "--log", Path("a2.lcm")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  LogReader log(Path("a2.lcm"));
  std::map<std::string, int> count;
  while (const std::optional<LogEvent> event = log.Next()) {
    ++count[event->channel];
    if (event->channel == "SIM_SCAN") {
      slammtt_msgs::laser_scan_t scan{};
      ASSERT_TRUE(Decode(event->data.data(), static_cast<int>(event->data.size()), &scan));
      EXPECT_EQ(scan.num_beams, 400);
      EXPECT_EQ(scan.valid.size(), 400u);
      EXPECT_FLOAT_EQ(scan.range_max_m, 12.0f);
      EXPECT_EQ(scan.scan_duration_us, 0);
      int valid = 0;
      for (int i = 0; i < scan.num_beams; ++i) {
        valid += scan.valid[static_cast<size_t>(i)];
        if (!scan.valid[static_cast<size_t>(i)]) {
          EXPECT_EQ(scan.range_m[static_cast<size_t>(i)], 0.0f);
        }
      }
      EXPECT_GT(valid, 10);
    }
  }
  EXPECT_EQ(count["ODOMETRY"], 41);
  EXPECT_EQ(count["GROUND_TRUTH"], 21);
  EXPECT_EQ(count["SIM_SCAN"], 21);
  EXPECT_EQ(count["FEATURES"], 21);
  EXPECT_EQ(count["LASER_GEOMETRY"], 3);  // frames 0, 10 and 20 (10 Hz)
  EXPECT_EQ(count.count("LASER_SCAN"), 0u);
}

TEST_F(WorldCliTest, OfficeGroundTruthNamesKindsLegsAndSegments) {
  const ProcessResult run =
      World({"--scenario", "office", "--duration", "30", "--log", Path("office.lcm")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  LogReader log(Path("office.lcm"));
  using slammtt_msgs::object_truth_t;
  int truths = 0;
  int scans = 0;
  int uneven_scans = 0;
  int person_beams = 0;
  while (const std::optional<LogEvent> event = log.Next()) {
    const int size = static_cast<int>(event->data.size());
    if (event->channel == "LASER_SCAN") {
      slammtt_msgs::laser_scan_t scan{};
      ASSERT_TRUE(Decode(event->data.data(), size, &scan));
      ++scans;
      uneven_scans += scan.num_beams != 400 ? 1 : 0;  // the A2's revolutions vary
      continue;
    }
    if (event->channel != "GROUND_TRUTH") continue;
    slammtt_msgs::ground_truth_t m{};
    ASSERT_TRUE(Decode(event->data.data(), size, &m));
    ++truths;
    ASSERT_EQ(m.num_segments, static_cast<int32_t>(m.segments.size()));
    ASSERT_EQ(m.num_segments, 58);  // 18 pieces of wall (one of glass), 10 boxes of 4 sides
    int walls = 0;
    for (const auto& segment : m.segments) {
      ASSERT_TRUE(segment.kind == object_truth_t::KIND_WALL ||
                  segment.kind == object_truth_t::KIND_FURNITURE);
      walls += segment.kind == object_truth_t::KIND_WALL;
    }
    EXPECT_EQ(walls, 18);
    std::map<int64_t, int> legs_of;
    std::map<int64_t, int> person_beams_of;
    for (size_t i = 0; i < m.objects.size(); ++i) {
      const auto& o = m.objects[i];
      if (o.kind == object_truth_t::KIND_PERSON) {
        EXPECT_EQ(o.object_class, +object_truth_t::CLASS_MOVING);
        EXPECT_EQ(o.parent_id, -1);
        person_beams_of[o.id] = o.beams_on_object;
        person_beams += o.beams_on_object;
      } else if (o.kind == object_truth_t::KIND_LEG) {
        ++legs_of[o.parent_id];
        person_beams_of[o.parent_id] -= o.beams_on_object;
        EXPECT_EQ(o.id, 10 * o.parent_id + legs_of[o.parent_id]);
      } else {
        EXPECT_TRUE(o.kind == object_truth_t::KIND_FURNITURE ||
                    o.kind == object_truth_t::KIND_POST);
        EXPECT_EQ(o.object_class, +object_truth_t::CLASS_STATIC);
      }
    }
    for (const auto& [person, legs] : legs_of) EXPECT_EQ(legs, 2) << person;
    for (const auto& [person, rest] : person_beams_of) EXPECT_EQ(rest, 0) << person;
  }
  EXPECT_EQ(truths, 301);
  EXPECT_EQ(scans, 301);
  EXPECT_GT(uneven_scans, 100);
  EXPECT_GT(person_beams, 0);
}

// Runs a bad scenario file; expects exit status 1, one error line starting with `expected`, and
// nothing left behind.
void ExpectRejected(const ProcessResult& run, const std::string& expected) {
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err.rfind("slammtt-world: error: " + expected, 0), 0u) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST_F(WorldCliTest, BadScenariosAreRejectedWithFileLineAndKeyAndLeaveNoLog) {
  struct Case {
    std::string yaml;
    std::string expected;  // after the file name
  };
  const std::vector<Case> cases = {
      {"duration_s: 5\nrobot:\n  speed: 1\n", ":3: robot.speed: unknown key"},
      {"duration_s: five\n", ":1: duration_s: expected a number, got \"five\""},
      {"statics:\n  - {x_m: 1, y_m: 1, radius_m: -0.2}\n",
       ":2: statics[0].radius_m: must be positive, got -0.2"},
      {"movers:\n  - type: trajectory\n    trajectory: [[0, 1, 1], [2, 2, 2], [1, 3, 3]]\n",
       ":3: movers[0].trajectory[2]: t_s: times must increase strictly"},
      {"crowd:\n  file: missing.tsv\n", ":2: crowd.file: "},
      {"robot:\n  profile:\n    - {duration_s: 1, linear_mps: 2.1}\n",
       ":3: robot.profile[0].linear_mps: must be within [-2, 2], got 2.1"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].yaml);
    const std::string scenario = Write("bad" + std::to_string(i) + ".yaml", cases[i].yaml);
    ExpectRejected(World({"--scenario", scenario, "--log", Path("out.lcm")}),
                   scenario + cases[i].expected);
    EXPECT_TRUE(LeftFiles().empty());
  }
}

TEST_F(WorldCliTest, BadTrajectoryFileIsRejectedWithItsLine) {
  Write("people.tsv", "t_s\tid\tx_m\ty_m\n0.0\t1\t1.0\t1.0\n0.4\t1\t2.0\n");
  const std::string scenario = Write("crowd.yaml", "crowd:\n  file: people.tsv\n");
  ExpectRejected(World({"--scenario", scenario, "--log", Path("out.lcm")}),
                 scenario + ":2: crowd.file: " + Path("people.tsv") + ":3: expected four");
  EXPECT_TRUE(LeftFiles().empty());
}

TEST_F(WorldCliTest, WaypointLoopWithATinyLapRuns) {
  // Used to build one knot per lap up to the horizon: 10^9 knots for 2 s, out of memory.
  const std::string scenario = Write(
      "tiny-loop.yaml",
      "duration_s: 2\nmovers:\n  - {type: waypoints, speed_mps: 1, at_end: loop,\n"
      "     waypoints: [[1, 0], [1, 0.000000001]]}\n");
  const ProcessResult run = World({"--scenario", scenario, "--log", Path("loop.lcm")});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(LeftFiles() == std::vector<std::string>{"loop.lcm"});
}

TEST_F(WorldCliTest, UnknownScenarioAndBadOptions) {
  ProcessResult run = World({"--scenario", "s9-nothing", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("scenario \"s9-nothing\" not found"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("s1-crossing"), std::string::npos) << run.err;
  run = World({"--scenario", "s1-crossing", "--seed", "-3", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  run = World({"--scenario", "s1-crossing", "--output", "pictures", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  run = World({"--scenario", "s1-crossing", "--duration", "0", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  run = World({"--scenario", "s1-crossing", "--duration", "2e6", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "slammtt-world: error: --duration must be within (0, 1e6] seconds\n");
  run = World({"--scenario", "s1-crossing", "--report", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);  // a report writes no log: asking for both is a mistake
  run = World({"--scenario", "s1-crossing", "--rate-factor", "5", "--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  run = World({"--log", Path("out.lcm")});
  EXPECT_EQ(run.exit_code, 2);
  run = World({"--scenario", "s1-crossing", "--log", Path("no-such-dir/out.lcm")});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_TRUE(LeftFiles().empty());
}

TEST_F(WorldCliTest, InterruptedLogRunLeavesNothing) {
  // 10^5 simulated seconds take tens of seconds: the run is still going when SIGINT comes.
  testing::ChildProcess world(
      {kWorld, "--scenario", "s1-crossing", "--duration", "100000", "--log", Path("long.lcm")},
      Path("long.out"), Path("long.err"));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  world.Signal(SIGINT);
  EXPECT_EQ(world.Wait(30000), 1);
  EXPECT_EQ(ReadWholeFile(Path("long.err")), "slammtt-world: error: interrupted: no log written\n");
  // Only the process's own output files remain: no log, no partial log (whatever its suffix).
  std::vector<std::string> left = LeftFiles();
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"long.err", "long.out"}));
}

TEST_F(WorldCliTest, ReportPrintsTheScenarioFigures) {
  const ProcessResult run = World({"--scenario", "s1-crossing", "--seed", "7", "--report"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.rfind("s1-crossing seed 7 output features duration 120 s\nscans 961,", 0), 0u)
      << run.out;
  EXPECT_NE(run.out.find("movers: 5"), std::string::npos);
  EXPECT_TRUE(LeftFiles().empty());
}

}  // namespace
}  // namespace slammtt
