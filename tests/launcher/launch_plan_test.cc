// The pure parts of slammtt-launch: the plan read from the robot: section, argument expansion,
// output line prefixing and the restart policy.
#include <gtest/gtest.h>

#include "drivers/launcher/launch_plan.h"
#include "drivers/launcher/line_prefixer.h"
#include "drivers/launcher/restart_policy.h"
#include "runtime/config.h"
#include "tests/support/options_table.h"

namespace slammtt {
namespace {

LaunchPlan Read(const std::string& yaml) {
  const Config config = Config::FromString(yaml, "robot.yaml");
  return ReadLaunchPlan(config.Child("robot"));
}

std::string ErrorOf(const std::string& yaml) {
  try {
    Read(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(LaunchPlanTest, DefaultsAndProcesses) {
  const LaunchPlan plan = Read(R"(
robot:
  processes:
    - name: p3dx
      program: slammtt-p3dx
    - name: logger
      program: lcm-logger
      args: ["--lcm-url={lcm_url}", "{log_file}"]
      pass_config: false
      stop_last: true
      restart: always
)");
  EXPECT_EQ(plan.log_directory, "logs");
  EXPECT_EQ(plan.network, BusNetwork::kLoopback);
  EXPECT_DOUBLE_EQ(plan.stop_grace_s, 5.0);
  EXPECT_EQ(plan.max_restarts, 5);
  EXPECT_EQ(plan.on_give_up, GiveUpAction::kStopAll);
  ASSERT_EQ(plan.processes.size(), 2u);
  EXPECT_EQ(plan.processes[0].name, "p3dx");
  EXPECT_TRUE(plan.processes[0].pass_config);
  EXPECT_FALSE(plan.processes[0].stop_last);
  EXPECT_EQ(plan.processes[0].restart, RestartMode::kOnFailure);
  EXPECT_EQ(plan.processes[1].args.size(), 2u);
  EXPECT_FALSE(plan.processes[1].pass_config);
  EXPECT_TRUE(plan.processes[1].stop_last);
  EXPECT_EQ(plan.processes[1].restart, RestartMode::kAlways);
}

TEST(LaunchPlanTest, EveryKeyIsRead) {
  const LaunchPlan plan = Read(R"(
robot:
  log_directory: /var/log/slammtt
  stop_grace_s: 2.5
  max_restarts: 3
  restart_initial_s: 0.5
  restart_max_s: 10
  restart_reset_after_s: 30
  on_give_up: keep_running
  network: lan
  processes:
    - {name: a, program: /bin/true, restart: never}
)");
  EXPECT_EQ(plan.network, BusNetwork::kLan);
  EXPECT_EQ(plan.log_directory, "/var/log/slammtt");
  EXPECT_DOUBLE_EQ(plan.stop_grace_s, 2.5);
  EXPECT_EQ(plan.max_restarts, 3);
  EXPECT_DOUBLE_EQ(plan.restart_initial_s, 0.5);
  EXPECT_DOUBLE_EQ(plan.restart_max_s, 10.0);
  EXPECT_DOUBLE_EQ(plan.restart_reset_after_s, 30.0);
  EXPECT_EQ(plan.on_give_up, GiveUpAction::kKeepRunning);
  EXPECT_EQ(plan.processes[0].restart, RestartMode::kNever);
}

TEST(LaunchPlanTest, MistakesAreErrorsNamingTheKey) {
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {name: a, program: x, colour: red}\n")
                .find("colour"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  log_dir: x\n  processes:\n    - {name: a, program: x}\n")
                .find("log_dir"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {name: a, program: x}\n    - {name: a, program: y}\n")
                .find("used twice"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {name: 'a b', program: x}\n").find("name"),
            std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {program: x}\n").find("name"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {name: a, program: x, restart: sometimes}\n")
                .find("restart"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes:\n    - {name: a, program: x, args: ['{home}']}\n")
                .find("{home}"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  on_give_up: panic\n  processes:\n    - {name: a, program: x}\n")
                .find("on_give_up"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  network: wifi\n  processes:\n    - {name: a, program: x}\n")
                .find("network: expected loopback or lan, got 'wifi'"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  stop_grace_s: 0\n  processes:\n    - {name: a, program: x}\n")
                .find("stop_grace_s"), std::string::npos);
  // A delay the supervisor could not turn into a poll timeout without overflow.
  EXPECT_NE(ErrorOf("robot:\n  restart_max_s: 1e300\n  processes:\n    - {name: a, program: x}\n")
                .find("restart_max_s"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  log_directory: x\n").find("processes"), std::string::npos);
  EXPECT_NE(ErrorOf("robot:\n  processes: []\n").find("processes"), std::string::npos);
  // Every message names the file and the line.
  EXPECT_EQ(ErrorOf("robot:\n  processes:\n    - {name: a, program: x, colour: red}\n").rfind("robot.yaml:", 0), 0u);
}

// The schemas name every key once, the reader reads every one (settings set to their defaults
// give the defaults), docs/robot.md carries the generated tables, and a plan built in code is
// checked by the same ranges.
TEST(LaunchPlanTest, EverySettingIsReadAndDocumented) {
  const std::string tables = LaunchPlanOptionsTables();
  const std::string process_heading = "Each entry of `processes`:";
  const size_t split = tables.find(process_heading);
  ASSERT_NE(split, std::string::npos) << tables;
  const auto rows = slammtt::testing::ParseOptionsTable(tables.substr(0, split));
  const auto process_rows = slammtt::testing::ParseOptionsTable(tables.substr(split));
  ASSERT_EQ(rows.size(), 8u) << tables;
  ASSERT_EQ(process_rows.size(), 3u) << tables;
  EXPECT_TRUE(slammtt::testing::KeysAreUnique(rows));
  std::string yaml = slammtt::testing::SectionOfDefaults("robot", rows) +
                     "  processes:\n    - name: a\n      program: x\n";
  for (const auto& row : process_rows) yaml += "      " + row.key + ": " + row.default_text + "\n";
  const LaunchPlan plan = Read(yaml);
  const LaunchPlan d;
  EXPECT_EQ(plan.network, d.network);
  EXPECT_EQ(plan.log_directory, d.log_directory);
  EXPECT_EQ(plan.restart_reset_after_s, d.restart_reset_after_s);
  EXPECT_EQ(plan.on_give_up, d.on_give_up);
  ASSERT_EQ(plan.processes.size(), 1u);
  EXPECT_EQ(plan.processes[0].pass_config, ProcessSpec().pass_config);
  EXPECT_EQ(plan.processes[0].restart, ProcessSpec().restart);
  const std::string docs = slammtt::testing::ReadCheckoutFile("docs/robot.md");
  ASSERT_FALSE(docs.empty()) << "docs/robot.md is part of the checkout";
  EXPECT_NE(docs.find(tables), std::string::npos)
      << "docs/robot.md: replace the robot: tables by `slammtt-launch --options-table`";

  LaunchPlan bad = plan;
  EXPECT_EQ(CheckLaunchPlan(bad), "");
  bad.stop_grace_s = 0.0;
  EXPECT_EQ(CheckLaunchPlan(bad), "stop_grace_s = 0: must be in (0, 86400]");
  bad = plan;
  bad.processes.push_back(bad.processes[0]);
  EXPECT_EQ(CheckLaunchPlan(bad), "processes[1].name 'a' is used twice");
  bad = plan;
  bad.processes[0].restart = static_cast<RestartMode>(7);
  EXPECT_EQ(CheckLaunchPlan(bad), "processes[0].restart is not one of its choices");
}

TEST(LaunchPlanTest, ArgumentsAreExpanded) {
  const std::map<std::string, std::string> variables = {
      {"config", "/etc/robot.yaml"}, {"lcm_url", "udpm://239.255.76.67:7667?ttl=0"},
      {"log_directory", "/var/log/slammtt"}, {"log_file", "/var/log/slammtt/x.lcm"}};
  EXPECT_EQ(ExpandLaunchArgument("--lcm-url={lcm_url}", variables),
            "--lcm-url=udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(ExpandLaunchArgument("{log_directory}/{{literal}}", variables),
            "/var/log/slammtt/{literal}");
  EXPECT_THROW(ExpandLaunchArgument("{nope}", variables), std::invalid_argument);
  EXPECT_THROW(ExpandLaunchArgument("{config", variables), std::invalid_argument);
  EXPECT_THROW(ExpandLaunchArgument("a}b", variables), std::invalid_argument);
  ProcessSpec spec;
  spec.args = {"--verbose", "{log_file}"};
  EXPECT_EQ(LaunchArguments(spec, "/etc/robot.yaml", variables),
            (std::vector<std::string>{"--config", "/etc/robot.yaml", "--verbose",
                                      "/var/log/slammtt/x.lcm"}));
  spec.pass_config = false;
  EXPECT_EQ(LaunchArguments(spec, "/etc/robot.yaml", variables).size(), 2u);
  EXPECT_EQ(LogFileName(2025, 1, 31, 14, 5, 9), "slammtt-20250131-140509.lcm");
}

TEST(LinePrefixerTest, PrefixesWholeLinesAcrossFeeds) {
  LinePrefixer prefixer(OutputPrefix("p3dx", 6));
  EXPECT_EQ(prefixer.Feed("hel", 3), "");
  EXPECT_EQ(prefixer.Feed("lo\nwor", 6), "p3dx   | hello\n");
  EXPECT_EQ(prefixer.Feed("ld\n\n", 4), "p3dx   | world\np3dx   | \n");
  EXPECT_EQ(prefixer.Feed("tail", 4), "");
  EXPECT_EQ(prefixer.Flush(), "p3dx   | tail\n");
  EXPECT_EQ(prefixer.Flush(), "");
}

TEST(LinePrefixerTest, CutsOverlongLines) {
  LinePrefixer prefixer("x| ", 4);
  EXPECT_EQ(prefixer.Feed("abcdefghij\n", 11), "x| abcd\nx| efgh\nx| ij\n");
  const std::string binary("a\0b\n", 4);
  EXPECT_EQ(prefixer.Feed(binary.data(), binary.size()), std::string("x| a\0b\n", 7));
}

TEST(RestartPolicyTest, BackoffDoublesUpToTheMaximumThenGivesUp) {
  LaunchPlan plan;
  plan.restart_initial_s = 1.0;
  plan.restart_max_s = 5.0;
  plan.max_restarts = 4;
  plan.restart_reset_after_s = 60.0;
  RestartPolicy policy(plan, RestartMode::kOnFailure);
  double t = 0.0;
  const double expected[] = {1.0, 2.0, 4.0, 5.0};
  for (double delay : expected) {
    const auto d = policy.OnExit(t, t + 0.5, false);
    ASSERT_TRUE(d.restart);
    EXPECT_DOUBLE_EQ(d.delay_s, delay);
    EXPECT_FALSE(d.gave_up);
    t += 10.0;
  }
  const auto last = policy.OnExit(t, t + 0.5, false);
  EXPECT_FALSE(last.restart);
  EXPECT_TRUE(last.gave_up);
}

TEST(RestartPolicyTest, ALongRunForgetsEarlierFailures) {
  LaunchPlan plan;
  plan.max_restarts = 2;
  plan.restart_reset_after_s = 60.0;
  RestartPolicy policy(plan, RestartMode::kOnFailure);
  EXPECT_TRUE(policy.OnExit(0, 1, false).restart);
  EXPECT_TRUE(policy.OnExit(2, 3, false).restart);
  const auto after_long_run = policy.OnExit(4, 100, false);  // ran 96 s
  EXPECT_TRUE(after_long_run.restart);
  EXPECT_DOUBLE_EQ(after_long_run.delay_s, plan.restart_initial_s);
}

TEST(RestartPolicyTest, ModesDecideAboutCleanExits) {
  LaunchPlan plan;
  RestartPolicy on_failure(plan, RestartMode::kOnFailure);
  const auto clean = on_failure.OnExit(0, 1, true);
  EXPECT_FALSE(clean.restart);
  EXPECT_FALSE(clean.gave_up);
  RestartPolicy always(plan, RestartMode::kAlways);
  EXPECT_TRUE(always.OnExit(0, 1, true).restart);
  RestartPolicy never(plan, RestartMode::kNever);
  const auto failed = never.OnExit(0, 1, false);
  EXPECT_FALSE(failed.restart);
  EXPECT_TRUE(failed.gave_up);
  EXPECT_FALSE(never.OnExit(0, 1, true).gave_up);
}

}  // namespace
}  // namespace slammtt
