// The runtime's visitors of an options schema (common/options_schema.h): the configuration
// reader (runtime/config_options.h) and the command-line options (runtime/command_line_options.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "runtime/command_line_options.h"
#include "runtime/config_options.h"

namespace slammtt {
namespace {

struct LinkOptions {
  std::string port = "/dev/ttyUSB0";
  int baud = 9600;
  double max_turn_radps = 1.0;
  bool enabled = true;
  int mode = 0;
  double min_s = 0.5;
  double max_s = 8.0;
};

void VisitLinkOptions(OptionVisitor* v, LinkOptions* o) {
  v->String("port", &o->port, "the device");
  v->Int("baud", &o->baud, OptionRange::Between(1, 10000000), "serial rate");
  v->Double("max_turn_radps", &o->max_turn_radps, OptionRange::Above(0), "turn-rate limit",
            OptionUnit::kDegrees);
  v->Bool("enabled", &o->enabled, "on or off");
  v->Choice("mode", &o->mode, {"standard", "express"}, "how");
  v->Double("min_s", &o->min_s, OptionRange::Above(0), "shortest");
  v->Double("max_s", &o->max_s, OptionRange::Above(0), "longest");
}

std::string ConfigErrorOf(const std::string& yaml, const std::string& problem) {
  const Config section = Config::FromString(yaml, "link.yaml").Child("link");
  try {
    FailOptionsProblem(section, problem);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigOptionsTest, TheReaderSetsPresentKeysInTheirUnitAndKeepsTheOthers) {
  const Config section =
      Config::FromString("link:\n  port: tcp://robot:4001\n  max_turn_degps: 90\n", "link.yaml")
          .Child("link");
  LinkOptions o;
  ConfigOptionReader reader(section);
  VisitLinkOptions(&reader, &o);
  EXPECT_EQ(o.port, "tcp://robot:4001");
  EXPECT_EQ(o.baud, 9600);
  EXPECT_EQ(o.max_turn_radps, 90.0 * M_PI / 180.0);
  EXPECT_NO_THROW(section.CheckUnused());
}

// A condition found after reading is reported at the line of the key it starts with, when the
// section sets it; a range problem reads as the reader's own message.
TEST(ConfigOptionsTest, AProblemIsReportedAtItsKeysLine) {
  EXPECT_EQ(ConfigErrorOf("link:\n  min_s: 2\n  max_s: 1\n", "max_s must be > min_s"),
            "link.yaml:3: link.max_s: must be > min_s");
  EXPECT_EQ(ConfigErrorOf("link:\n  baud: 0\n", "baud = 0: must be in [1, 1e+07]"),
            "link.yaml:2: link.baud: must be in [1, 1e+07], got 0");
  // The key is not in the section: the problem as it is, at the section.
  EXPECT_EQ(ConfigErrorOf("link:\n  min_s: 20\n", "max_s must be > min_s"),
            "link.yaml:2: link: max_s must be > min_s");
}

CommandLine Parsed(const CommandLineOptions& flags, std::vector<const char*> args) {
  CommandLine command_line("prog", "[options]", "test");
  flags.Declare(&command_line, VisitLinkOptions);
  args.insert(args.begin(), "prog");
  command_line.Parse(static_cast<int>(args.size()), args.data());
  return command_line;
}

// Only the keys named get an option, --KEY with '-' for '_'; values in the configuration's unit,
// held to the schema's range; the help says the section key, the default and the range.
TEST(ConfigOptionsTest, CommandLineOptionsComeFromTheSchema) {
  const CommandLineOptions flags({"port", "baud", "max_turn_degps", "enabled", "mode"}, "link");
  EXPECT_EQ(CommandLineOptions::FlagOf("max_turn_degps"), "--max-turn-degps");
  LinkOptions o;
  flags.Apply(Parsed(flags, {"--port", "/dev/ttyACM0", "--baud", "115200", "--enabled", "false",
                             "--mode", "express", "--max-turn-degps", "45"}),
              VisitLinkOptions, &o);
  EXPECT_EQ(o.port, "/dev/ttyACM0");
  EXPECT_EQ(o.baud, 115200);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.mode, 1);
  // An angle's option is its key (in degrees) and takes degrees, as the configuration does.
  EXPECT_EQ(o.max_turn_radps, 45.0 * M_PI / 180.0);
  const auto usage_error = [&](std::vector<const char*> args) {
    LinkOptions options;
    try {
      flags.Apply(Parsed(flags, args), VisitLinkOptions, &options);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(usage_error({"--baud", "0"}), "--baud: must be in [1, 1e+07], got 0");
  EXPECT_EQ(usage_error({"--mode", "turbo"}), "--mode: expected standard or express, got 'turbo'");
  EXPECT_EQ(usage_error({"--enabled", "yes"}), "--enabled: expected true or false, got 'yes'");
  // A key not named has no option.
  EXPECT_THROW(Parsed(flags, {"--min-s", "1"}), UsageError);
  const std::string help = Parsed(flags, {}).Help();
  EXPECT_NE(help.find("serial rate (link.baud, default 9600, [1, 1e+07])"), std::string::npos)
      << help;
}

}  // namespace
}  // namespace slammtt
