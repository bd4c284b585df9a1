// Scenario files: values and defaults, and every kind of bad input rejected with one line that
// names the file, the line and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "tests/support/child_process.h"
#include "tests/support/options_table.h"
#include "tools/world/scenario_loader.h"
#include "tools/world/scenario_options.h"

namespace slammtt {
namespace {

namespace fs = std::filesystem;

class ScenarioLoaderTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  // The ConfigError message of loading `yaml` (empty when it loads).
  std::string ErrorOf(const std::string& yaml) {
    const std::string path = Write("bad.yaml", yaml);
    try {
      LoadScenario(path);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
  std::string BadPath() const { return (dir_ / "bad.yaml").string(); }

  testing::TempDir temp_{"slammtt-world-loader"};  // removed with its content after the test
  const fs::path dir_ = temp_.path();
};

TEST_F(ScenarioLoaderTest, ReadsEveryKindOfObjectWithDefaults) {
  const std::string path = Write("ok.yaml", R"(name: ok
duration_s: 30
output: features
laser: {fov_deg: 180, resolution_deg: 1, max_range_m: 30, rate_hz: 8, mount_a_m: 0.1}
features: {range_noise_m: 0.2, bearing_noise_deg: 2}
odometry: {rate_hz: 20, slip_std: 0.01}
robot:
  start: {x_m: 1, y_m: 2, heading_deg: 90}
  profile:
    - {duration_s: 10, linear_mps: 1.5, angular_degps: 0}
    - {duration_s: 5, linear_mps: 0.5, angular_degps: 18}
statics:
  - {x_m: 5, y_m: 2, radius_m: 0.3}
  - {id: 7, x_m: -5, y_m: 2}
movers:
  - {id: 101, type: constant_velocity, start: [8, -3], velocity_mps: [0.625, 0.625]}
  - {id: 102, type: waypoints, waypoints: [[0, 0], [3, 0, 2.5]], speed_mps: 1.2, at_end: leave}
  - {id: 103, type: trajectory, trajectory: [[0, 1, 1], [1, 2, 1]], appear_s: 0.5}
  - {id: 104, type: random_walk, start: [0, 0], area: [-5, -5, 5, 5], max_turn_deg: 180,
     reverse_probability: 0.1, radius_m: 0.2, disappear_s: 20}
)");
  const Scenario s = LoadScenario(path);
  EXPECT_EQ(s.name, "ok");
  EXPECT_EQ(s.duration_s, 30.0);
  EXPECT_EQ(s.output, SensorOutput::kFeatures);
  EXPECT_EQ(s.laser.fov_deg, 180.0);
  EXPECT_EQ(s.laser.mount_a_m, 0.1);
  EXPECT_EQ(s.laser.min_range_m, LaserSpec{}.min_range_m);
  EXPECT_EQ(s.odometry.slip_std, 0.01);
  EXPECT_NEAR(s.robot.start.heading_rad, M_PI / 2, 1e-12);
  ASSERT_EQ(s.robot.profile.size(), 2u);
  EXPECT_NEAR(s.robot.profile[1].angular_radps, 18.0 * M_PI / 180.0, 1e-12);
  ASSERT_EQ(s.statics.size(), 2u);
  EXPECT_EQ(s.statics[0].id, 1);  // default id: position in the list
  EXPECT_EQ(s.statics[1].id, 7);
  EXPECT_EQ(s.statics[1].radius_m, StaticObjectSpec{}.radius_m);
  ASSERT_EQ(s.movers.size(), 4u);
  EXPECT_EQ(s.movers[0].kind, MoverKind::kConstantVelocity);
  EXPECT_EQ(s.movers[0].vx_mps, 0.625);
  EXPECT_EQ(s.movers[1].kind, MoverKind::kWaypoints);
  EXPECT_EQ(s.movers[1].waypoints[1].wait_s, 2.5);
  EXPECT_EQ(s.movers[1].at_end, PathEnd::kLeave);
  EXPECT_EQ(s.movers[2].kind, MoverKind::kTrajectory);
  EXPECT_EQ(s.movers[2].trajectory[1].x_m, 2.0);
  EXPECT_EQ(s.movers[3].kind, MoverKind::kRandomWalk);
  EXPECT_NEAR(s.movers[3].random_walk.max_turn_rad, M_PI, 1e-12);
  EXPECT_EQ(s.movers[3].random_walk.area_max_y_m, 5.0);
  EXPECT_EQ(s.movers[3].disappear_s, 20.0);
}

TEST_F(ScenarioLoaderTest, NameDefaultsToTheFileName) {
  EXPECT_EQ(LoadScenario(Write("my-world.yaml", "duration_s: 5\n")).name, "my-world");
}

TEST_F(ScenarioLoaderTest, UnknownTopLevelKeyNamesFileLineAndKey) {
  const std::string error = ErrorOf("duration_s: 5\ncolour: red\n");
  EXPECT_EQ(error.rfind(BadPath() + ":2: colour: unknown key", 0), 0u) << error;
}

TEST_F(ScenarioLoaderTest, UnknownKeyOfAMoverTypeNamesIt) {
  const std::string error = ErrorOf(R"(movers:
  - type: waypoints
    waypoints: [[0, 0], [1, 1]]
    velocity_mps: [1, 0]
)");
  EXPECT_EQ(error.rfind(BadPath() + ":4: movers[0].velocity_mps: unknown key", 0), 0u) << error;
}

TEST_F(ScenarioLoaderTest, UnknownKeyInsideASectionNamesIt) {
  const std::string error = ErrorOf("laser:\n  fov_deg: 180\n  max_range: 30\n");
  EXPECT_EQ(error.rfind(BadPath() + ":3: laser.max_range: unknown key", 0), 0u) << error;
}

TEST_F(ScenarioLoaderTest, KeyGivenTwiceNamesBothLines) {
  // The second value used to be dropped silently (the YAML library keeps the first).
  EXPECT_EQ(ErrorOf("laser:\n  fov_deg: 180\n  fov_deg: 360\n"),
            BadPath() + ":3: laser.fov_deg: duplicate key (first at line 2)");
  EXPECT_EQ(ErrorOf("duration_s: 5\nstatics:\n  - {x_m: 1, y_m: 2, x_m: 3}\n"),
            BadPath() + ":3: statics[0].x_m: duplicate key (first at line 3)");
  EXPECT_EQ(ErrorOf("duration_s: 5\nduration_s: 6\n"),
            BadPath() + ":2: duration_s: duplicate key (first at line 1)");
}

TEST_F(ScenarioLoaderTest, WrongTypeNamesFileLineAndKey) {
  const std::string error = ErrorOf("name: x\nduration_s: long\n");
  EXPECT_EQ(error, BadPath() + ":2: duration_s: expected a number, got \"long\"");
  const std::string list_error =
      ErrorOf("movers:\n  - {type: constant_velocity, start: 3, velocity_mps: [1, 0]}\n");
  EXPECT_NE(list_error.find(BadPath() + ":2: movers[0].start: expected a list of numbers"),
            std::string::npos)
      << list_error;
}

TEST_F(ScenarioLoaderTest, NegativeRadiusNamesFileLineAndKey) {
  const std::string error = ErrorOf(R"(statics:
  - {x_m: 1, y_m: 2, radius_m: 0.3}
  - x_m: 4
    y_m: 2
    radius_m: -0.3
)");
  EXPECT_EQ(error, BadPath() + ":5: statics[1].radius_m: must be positive, got -0.3");
}

TEST_F(ScenarioLoaderTest, NonIncreasingTrajectoryTimesNameTheLine) {
  const std::string error = ErrorOf(R"(movers:
  - type: trajectory
    trajectory:
      - [0.0, 1, 1]
      - [0.4, 2, 1]
      - [0.4, 3, 1]
)");
  EXPECT_EQ(error, BadPath() +
                       ":6: movers[0].trajectory[2]: t_s: times must increase strictly, got 0.4 "
                       "after 0.4");
}

TEST_F(ScenarioLoaderTest, RobotFasterThanTwoMetresPerSecondIsRejected) {
  const std::string error = ErrorOf(R"(robot:
  profile:
    - {duration_s: 3, linear_mps: 2.5}
)");
  EXPECT_EQ(error, BadPath() + ":3: robot.profile[0].linear_mps: must be within [-2, 2], got 2.5");
  const std::string waypoint_error =
      ErrorOf("robot:\n  waypoints: [[1, 0], [2, 0]]\n  speed_mps: 3\n");
  EXPECT_EQ(waypoint_error, BadPath() + ":3: robot.speed_mps: must be in (0, 2], got 3");
}

TEST_F(ScenarioLoaderTest, OtherValueChecksNameTheirKeys) {
  EXPECT_EQ(ErrorOf("laser: {fov_deg: 400}\n"),
            BadPath() + ":1: laser.fov_deg: must be in (0, 360], got 400");
  EXPECT_EQ(ErrorOf("output: pictures\n"),
            BadPath() + ":1: output: expected features, scans or both, got 'pictures'");
  EXPECT_EQ(ErrorOf("movers:\n  - {type: teleport}\n").rfind(BadPath() + ":2: movers[0].type:", 0),
            0u);
  EXPECT_EQ(ErrorOf("statics:\n  - {id: 3, x_m: 0, y_m: 0}\n  - {id: 3, x_m: 1, y_m: 0}\n"),
            BadPath() + ":3: statics[1].id: duplicate object id 3");
  EXPECT_EQ(ErrorOf("movers:\n  - {type: random_walk, start: [9, 9], area: [0, 0, 5, 5]}\n"),
            BadPath() + ":2: movers[0].start: must lie inside the area");
  EXPECT_EQ(ErrorOf("duration_s: -1\n"),
            BadPath() + ":1: duration_s: must be in (0, 1e+06], got -1");
  // Magnitudes that would overflow are refused, not simulated.
  EXPECT_EQ(ErrorOf("duration_s: 1e300\n"),
            BadPath() + ":1: duration_s: must be in (0, 1e+06], got 1e+300");
  EXPECT_EQ(ErrorOf("statics:\n  - {x_m: 1e200, y_m: 0}\n"),
            BadPath() + ":2: statics[0].x_m: must be within +-1e+06 m, got 1e+200");
  EXPECT_EQ(
      ErrorOf("movers:\n  - {type: constant_velocity, start: [0, 0], velocity_mps: [1e9, 0]}\n"),
            BadPath() + ":2: movers[0].velocity_mps: speed must not exceed 50 m/s");
}

// The settings' schemas name every key once, the loader reads every one (a file that sets each
// key to its default gives the defaults), and docs/world.md carries the generated tables.
TEST_F(ScenarioLoaderTest, EverySettingOfTheSchemasIsReadAndDocumented) {
  std::string yaml;
  size_t keys = 0;
  for (const auto& [section, table] : ScenarioOptionsTables()) {
    const std::vector<slammtt::testing::OptionsTableRow> rows =
        slammtt::testing::ParseOptionsTable(table);
    EXPECT_TRUE(slammtt::testing::KeysAreUnique(rows)) << section;
    keys += rows.size();
    if (section.empty()) {
      for (const auto& row : rows) yaml += row.key + ": " + row.default_text + "\n";
    } else {
      yaml += slammtt::testing::SectionOfDefaults(section, rows);
    }
  }
  EXPECT_EQ(keys, 3u + 17u + 3u + 7u + 5u + 3u + 6u);
  const Scenario s = LoadScenarioFromString(yaml, "every.yaml", ".");
  const Scenario d;
  EXPECT_EQ(s.duration_s, d.duration_s);
  EXPECT_EQ(s.start_utime, d.start_utime);
  EXPECT_EQ(s.output, d.output);
  EXPECT_EQ(s.laser.fov_deg, d.laser.fov_deg);
  EXPECT_EQ(s.laser.artefacts.beam_divergence_deg, d.laser.artefacts.beam_divergence_deg);
  EXPECT_EQ(s.features.bearing_noise_deg, d.features.bearing_noise_deg);
  EXPECT_EQ(s.odometry.wheel_radius_m, d.odometry.wheel_radius_m);
  EXPECT_EQ(s.legs.radius_m, d.legs.radius_m);
  EXPECT_EQ(s.robot.turn_gain_per_s, d.robot.turn_gain_per_s);
  // Written as 57.2958 deg/s (six digits): within 1e-6 of 1 rad/s.
  EXPECT_NEAR(s.robot.max_angular_radps, d.robot.max_angular_radps, 1e-6);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/world.md");
  ASSERT_FALSE(docs.empty()) << "docs/world.md is part of the checkout";
  EXPECT_NE(docs.find(ScenarioOptionsMarkdown()), std::string::npos)
      << "docs/world.md: replace the settings' tables by `slammtt-world --options-table`";
}

// A condition between settings names the line of its key; a scenario built in code gets the
// schema's check through FindScenarioProblems.
TEST_F(ScenarioLoaderTest, SettingsConditionsNameTheirLine) {
  EXPECT_EQ(ErrorOf("laser:\n  min_range_m: 5\n  max_range_m: 4\n"),
            BadPath() + ":3: laser.max_range_m: must exceed laser.min_range_m");
  EXPECT_EQ(ErrorOf("robot:\n  max_angular_degps: 0\n"),
            BadPath() + ":2: robot.max_angular_degps: must be > 0, got 0");
  Scenario s;
  s.odometry.right_slip_bias = 0.7;
  s.laser.rate_hz = 0.0;
  const std::vector<std::string> problems = FindScenarioProblems(s);
  ASSERT_FALSE(problems.empty());
  EXPECT_EQ(problems.front(), "laser.rate_hz: must be in [0.01, 1000], got 0");
  s.laser.rate_hz = 10.0;
  EXPECT_EQ(FindScenarioProblems(s).front(),
            "odometry.right_slip_bias: must be in [-0.5, 0.5], got 0.7");
}

TEST_F(ScenarioLoaderTest, MissingScenarioFileIsAnError) {
  try {
    LoadScenario((dir_ / "nothing.yaml").string());
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "nothing.yaml").string() + ": cannot open file");
  }
}

TEST_F(ScenarioLoaderTest, ADirectoryIsNotAScenario) {
  EXPECT_THROW(LoadScenario(dir_.string()), ConfigError);
  EXPECT_THROW(ReadRecordedTracks(dir_.string()), ConfigError);
}

TEST_F(ScenarioLoaderTest, MissingTrajectoryFileNamesTheScenarioKeyAndThePath) {
  const std::string error = ErrorOf("duration_s: 5\ncrowd:\n  file: people/none.tsv\n");
  EXPECT_EQ(error.rfind(BadPath() + ":3: crowd.file: ", 0), 0u) << error;
  EXPECT_NE(error.find("people/none.tsv: cannot open file"), std::string::npos) << error;
}

TEST_F(ScenarioLoaderTest, CrowdFileIsReadRelativeToTheScenarioAndTransformed) {
  fs::create_directories(dir_ / "data");
  Write("data/people.tsv",
        "t_s\tid\tx_m\ty_m\n0.0\t1\t1.0\t0.0\n0.0\t2\t5.0\t5.0\n0.4\t1\t2.0\t0.0\n"
        "0.4\t2\t5.0\t6.0\n0.8\t1\t3.0\t0.0\n");
  const Scenario s = LoadScenario(Write("crowd.yaml", R"(duration_s: 5
crowd:
  file: data/people.tsv
  window_s: [0.4, 100]
  offset_m: [10, 0]
  rotation_deg: 0
  radius_m: 0.3
  id_offset: 500
)"));
  // Person 2 has one sample in the window: skipped.
  ASSERT_EQ(s.movers.size(), 1u);
  EXPECT_EQ(s.movers[0].id, 501);
  EXPECT_EQ(s.movers[0].radius_m, 0.3);
  ASSERT_EQ(s.movers[0].trajectory.size(), 2u);
  EXPECT_NEAR(s.movers[0].trajectory[0].t_s, 0.0, 1e-12);
  EXPECT_NEAR(s.movers[0].trajectory[0].x_m, 12.0, 1e-12);
}

TEST_F(ScenarioLoaderTest, TrajectoryFileErrorsNameTheirLine) {
  const std::string bad_row =
      Write("a.tsv", "t_s\tid\tx_m\ty_m\n0.0\t1\t1.0\t0.0\n0.4\t1\tx\t0.0\n");
  try {
    ReadRecordedTracks(bad_row);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              bad_row + ":3: expected four tab-separated numbers t_s, id, x_m, y_m");
  }
  const std::string backwards =
      Write("b.tsv", "t_s\tid\tx_m\ty_m\n0.4\t1\t1.0\t0.0\n0.4\t2\t1.0\t0.0\n0.0\t1\t1.0\t0.0\n");
  try {
    ReadRecordedTracks(backwards);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              backwards + ":4: person 1: time 0 does not increase (previous 0.4)");
  }
  const std::string header = Write("c.tsv", "time,id,x,y\n");
  EXPECT_THROW(ReadRecordedTracks(header), ConfigError);
  // Ids so large that id_offset + id would overflow (undefined behaviour) are refused.
  const std::string huge_id =
      Write("d.tsv", "t_s\tid\tx_m\ty_m\n0.0\t9223372036854775807\t1\t1\n");
  try {
    ReadRecordedTracks(huge_id);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), huge_id + ":2: person id must be within +-1e15");
  }
}

TEST_F(ScenarioLoaderTest, CrowdIdOffsetIsBounded) {
  Write("people.tsv", "t_s\tid\tx_m\ty_m\n0.0\t1\t1\t1\n0.4\t1\t2\t2\n");
  EXPECT_EQ(ErrorOf("crowd:\n  file: people.tsv\n  id_offset: 9223372036854775807\n"),
            BadPath() + ":3: crowd.id_offset: must be within +-1e15 (mover id = id_offset + "
                        "recorded id)");
  EXPECT_EQ(ErrorOf("crowd:\n  file: people.tsv\n  id_offset: 1000000000000000\n"), "");
}

TEST_F(ScenarioLoaderTest, ResolveFindsNamesAndListsShippedScenarios) {
  fs::create_directories(dir_ / "root" / "config" / "scenarios");
  Write("root/config/scenarios/alpha.yaml", "duration_s: 1\n");
  const std::string root = (dir_ / "root").string();
  EXPECT_EQ(ResolveScenarioPath("alpha", {"/nonexistent", root}),
            (dir_ / "root" / "config" / "scenarios" / "alpha.yaml").string());
  try {
    ResolveScenarioPath("beta", {root});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("shipped scenarios: alpha"), std::string::npos);
  }
  EXPECT_THROW(ResolveScenarioPath("./beta.yaml", {root}), ConfigError);
}

TEST_F(ScenarioLoaderTest, RoomsFurnitureAndLeggedPeopleInAFewLines) {
  const Scenario s = LoadScenarioFromString(R"(
people: legs
legs: {radius_m: 0.055, hip_width_m: 0.22}
laser: {mixed_pixel_probability: 0.5, grazing_dropout_deg: 80, range_noise_per_m: 0.002,
        sample_rate_hz: 4000, rotation_jitter: 0.01, angle_jitter_deg: 0.1}
statics:
  - {type: polygon, vertices: [[0, 0], [6, 0], [6, 4], [0, 4]], openings: [[0, 2, 0.9]]}
  - {type: box, center: [2, 2], size_m: [1.6, 0.8], heading_deg: 90, dropout_probability: 0.3}
  - {type: chair, center: [3, 2]}
  - {type: table, center: [4, 2], size_m: [1, 1], kind: furniture}
  - {x_m: 5, y_m: 1}
  - {type: polyline, vertices: [[0, 5], [10, 5]], kind: furniture}
movers:
  - {type: constant_velocity, start: [1, 1], velocity_mps: [1, 0]}
  - {type: constant_velocity, start: [1, 2], velocity_mps: [1, 0], body: disc}
)",
                                            "inline", ".");
  EXPECT_EQ(s.people, MoverBody::kLegs);
  EXPECT_DOUBLE_EQ(s.legs.radius_m, 0.055);
  EXPECT_DOUBLE_EQ(s.legs.hip_width_m, 0.22);
  EXPECT_DOUBLE_EQ(s.laser.artefacts.mixed_pixel_probability, 0.5);
  EXPECT_DOUBLE_EQ(s.laser.artefacts.grazing_dropout_deg, 80.0);
  EXPECT_DOUBLE_EQ(s.laser.artefacts.sample_rate_hz, 4000.0);
  ASSERT_EQ(s.statics.size(), 6u);
  EXPECT_EQ(s.statics[0].shape, StaticShape::kPolygon);
  EXPECT_EQ(s.statics[0].kind, ObjectKind::kWall);
  ASSERT_EQ(s.statics[0].openings.size(), 1u);
  EXPECT_DOUBLE_EQ(s.statics[0].openings[0].width_m, 0.9);
  EXPECT_EQ(s.statics[1].shape, StaticShape::kBox);
  EXPECT_EQ(s.statics[1].kind, ObjectKind::kFurniture);
  EXPECT_NEAR(s.statics[1].heading_rad, M_PI / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.statics[1].dropout_probability, 0.3);
  EXPECT_EQ(s.statics[2].shape, StaticShape::kLegs);
  EXPECT_DOUBLE_EQ(s.statics[2].size_x_m, 0.45);
  EXPECT_DOUBLE_EQ(s.statics[2].leg_radius_m, 0.015);
  EXPECT_DOUBLE_EQ(s.statics[3].size_x_m, 1.0);
  EXPECT_DOUBLE_EQ(s.statics[3].leg_radius_m, 0.025);
  EXPECT_EQ(s.statics[4].kind, ObjectKind::kPost);
  EXPECT_EQ(s.statics[5].kind, ObjectKind::kFurniture);
  // Default ids count on past the four ids of each chair and table.
  EXPECT_EQ(s.statics[0].id, 1);
  EXPECT_EQ(s.statics[2].id, 3);
  EXPECT_EQ(s.statics[3].id, 7);
  EXPECT_EQ(s.statics[4].id, 11);
  EXPECT_EQ(s.statics[5].id, 12);
  EXPECT_EQ(BodyOf(s, s.movers[0]), MoverBody::kLegs);
  EXPECT_EQ(BodyOf(s, s.movers[1]), MoverBody::kDisc);
}

TEST_F(ScenarioLoaderTest, BadRoomsAndPeopleNameFileLineAndKey) {
  EXPECT_EQ(ErrorOf("statics:\n  - {type: polygon, vertices: [[0, 0], [4, 0], [4, 3]],\n"
                    "     openings: [[0, 3.5, 1]]}\n"),
            BadPath() +
                ":3: statics[0].openings[0]: must lie within side 0 (length 4 m) with offset >= "
                "0 and width > 0");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: polygon, vertices: [[0, 0], [4, 0]]}\n"),
            BadPath() + ":2: statics[0].vertices: a polygon needs at least 3 vertices");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: wall}\n"),
            BadPath() + ":2: statics[0].type: expected circle, polygon, polyline, box, chair or "
                        "table, got \"wall\"");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: box, center: [0, 0], size_m: [1, 1], kind: glass}\n"),
            BadPath() + ":2: statics[0].kind: expected wall, furniture or post, got \"glass\"");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: box, center: [0, 0], size_m: [1, -1]}\n"),
            BadPath() + ":2: statics[0].size_m: must be positive, got -1");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: chair, center: [0, 0], radius_m: 1}\n"),
            BadPath() + ":2: statics[0].radius_m: unknown key (known here: id, type, kind, "
                        "dropout_probability, center, size_m, heading_deg, leg_radius_m)");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: polyline, vertices: [[0, 0], [1, 0]], "
                    "openings: [[0.5, 0, 0.1]]}\n"),
            BadPath() + ":2: statics[0].openings[0]: side must be a whole number >= 0");
  EXPECT_EQ(ErrorOf("statics:\n  - {type: chair, id: 5, center: [0, 0]}\n  - {id: 7, x_m: 3, "
                    "y_m: 0}\n"),
            BadPath() + ":3: statics[1].id: duplicate object id 7");
  EXPECT_EQ(ErrorOf("people: crowds\n"),
            BadPath() + ":1: people: expected discs or legs, got \"crowds\"");
  EXPECT_EQ(ErrorOf("movers:\n  - {type: constant_velocity, start: [0, 0], velocity_mps: [1, 0],"
                    " body: wheel}\n"),
            BadPath() + ":2: movers[0].body: expected disc or legs, got \"wheel\"");
  EXPECT_EQ(ErrorOf("legs: {radius_m: 0.9}\n"),
            BadPath() + ":1: legs.radius_m: must be in [0.001, 0.5], got 0.9");
  // A person's legs take ids 10 * id + 1 and + 2.
  EXPECT_EQ(ErrorOf("people: legs\nstatics:\n  - {id: 11, x_m: 5, y_m: 5}\nmovers:\n"
                    "  - {id: 1, type: constant_velocity, start: [0, 0], velocity_mps: [1, 0]}\n"),
            BadPath() + ":5: movers[0].id: duplicate object id 11");
  EXPECT_EQ(ErrorOf("laser: {grazing_dropout_deg: 0}\n"),
            BadPath() + ":1: laser.grazing_dropout_deg: must be in (0, 90], got 0");
  EXPECT_EQ(ErrorOf("laser: {sample_rate_hz: 5}\n"),
            BadPath() + ":1: laser.sample_rate_hz: must be 0 (even beams) or within [10, 1e6], "
                        "got 5");
  EXPECT_EQ(ErrorOf("laser: {sample_rate_hz: 4000, fov_deg: 270}\n"),
            BadPath() + ":1: laser.sample_rate_hz: sampled beam angles need a 360-degree laser "
                        "(fov_deg 360)");
  EXPECT_EQ(ErrorOf("laser: {mixed_pixel_probability: 1.5}\n"),
            BadPath() + ":1: laser.mixed_pixel_probability: must be in [0, 1], got 1.5");
  EXPECT_EQ(ErrorOf("statics:\n  - {x_m: 0, y_m: 0, dropout_probability: -0.1}\n"),
            BadPath() + ":2: statics[0].dropout_probability: must be within [0, 1], got -0.1");
}

}  // namespace
}  // namespace slammtt
