#include "runtime/config.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>

namespace slammtt {
namespace {

TEST(ConfigTest, ReadsTypedValuesAndDefaults) {
  const Config c = Config::FromString(
      "segmenter:\n  lambda_deg: 20\n  sigma_r_m: 0.03\n  centre: circle\n  enabled: true\n"
      "  list: [1, 2.5]\n",
      "test.yaml");
  const Config s = c.Child("segmenter");
  EXPECT_DOUBLE_EQ(s.GetDouble("lambda_deg", 0.0), 20.0);
  EXPECT_DOUBLE_EQ(s.GetDouble("sigma_r_m", 0.0), 0.03);
  EXPECT_EQ(s.GetString("centre", ""), "circle");
  EXPECT_TRUE(s.GetBool("enabled", false));
  EXPECT_EQ(s.GetDoubles("list", {}), (std::vector<double>{1.0, 2.5}));
  EXPECT_EQ(s.GetInt("min_points", 3), 3);
  EXPECT_NO_THROW(c.CheckUnused());
}

TEST(ConfigTest, UnknownKeyIsAnErrorNamingFileLineAndPath) {
  const Config c = Config::FromString("segmenter:\n  lambda_deg: 20\n  lamda_deg: 21\n", "a.yaml");
  const Config s = c.Child("segmenter");
  s.GetDouble("lambda_deg", 0.0);
  try {
    c.CheckUnused();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "a.yaml:3: segmenter.lamda_deg: unknown key");
  }
}

TEST(ConfigTest, WrongTypeNamesTheKeyAndTheValue) {
  const Config c = Config::FromString("radius_m: big\n", "s.yaml");
  try {
    c.GetDouble("radius_m", 1.0);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:1: radius_m: expected a number, got \"big\"");
  }
}

TEST(ConfigTest, RejectsNonFiniteNumbersAndFractionalIntegers) {
  const Config c = Config::FromString("a: .nan\nb: .inf\nc: 2.5\n", "s.yaml");
  EXPECT_THROW(c.GetDouble("a", 0), ConfigError);
  EXPECT_THROW(c.GetDouble("b", 0), ConfigError);
  EXPECT_THROW(c.GetInt("c", 0), ConfigError);
}

TEST(ConfigTest, MissingRequiredKey) {
  const Config c = Config::FromString("objects:\n  - {x_m: 1}\n", "s.yaml");
  const std::vector<Config> objects = c.Items("objects");
  ASSERT_EQ(objects.size(), 1u);
  try {
    objects[0].RequireDouble("radius_m");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:2: objects[0].radius_m: missing key");
  }
}

TEST(ConfigTest, UnusedKeyInsideAListElementIsFound) {
  const Config c =
      Config::FromString("objects:\n  - x_m: 1\n  - x_m: 2\n    colour: red\n", "s.yaml");
  for (const Config& o : c.Items("objects")) o.GetDouble("x_m", 0);
  try {
    c.CheckUnused();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:4: objects[1].colour: unknown key");
  }
}

TEST(ConfigTest, BadYamlAndMissingFile) {
  EXPECT_THROW(Config::FromString("a: [1, 2\n", "bad.yaml"), ConfigError);
  EXPECT_THROW(Config::FromString("- 1\n- 2\n", "list.yaml"), ConfigError);
  EXPECT_THROW(Config::LoadFile("/nonexistent/slammtt.yaml"), ConfigError);
  EXPECT_NO_THROW(Config::FromString("", "empty.yaml"));
}

// Before: a directory read as an empty configuration (every default, silently), and /dev/zero
// was read until memory ran out (21.7 GB after 87 s in slammtt-segmenter --config /dev/zero).
TEST(ConfigTest, AFileThatIsNoConfigurationIsOneLineAndReadsNothing) {
  char directory[] = "/tmp/config-test-XXXXXX";
  ASSERT_NE(mkdtemp(directory), nullptr);
  const std::string fifo = std::string(directory) + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string big = std::string(directory) + "/big.yaml";
  std::fclose(std::fopen(big.c_str(), "w"));
  ASSERT_EQ(truncate(big.c_str(), 17 << 20), 0);  // sparse: 17 MiB of zeros
  const struct {
    std::string path;
    const char* says;
  } cases[] = {{directory, "not a regular file"},
               {"/dev/zero", "not a regular file"},
               {fifo, "not a regular file"},
               {big, "17825792 bytes is not a configuration (at most 16777216)"}};
  for (const auto& c : cases) {
    try {
      Config::LoadFile(c.path);
      ADD_FAILURE() << c.path << " accepted";
    } catch (const ConfigError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(c.path + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  unlink(big.c_str());
  unlink(fifo.c_str());
  rmdir(directory);
}

TEST(ConfigTest, NonTextKeyIsAConfigErrorNamingTheFile) {
  const Config c = Config::FromString("world:\n  [1, 2]: 3\n", "k.yaml");
  const Config w = c.Child("world");
  try {
    w.Keys();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "k.yaml:2: world: keys must be plain text, got a list");
  }
  EXPECT_THROW(c.CheckUnused(), ConfigError);
}

TEST(ConfigTest, KeyGivenTwiceIsAnErrorNamingBothLines) {
  // yaml-cpp keeps both entries and every lookup finds the first: 180 would win silently.
  const Config c =
      Config::FromString("laser:\n  fov_deg: 180\n  rate_hz: 8\n  fov_deg: 360\n", "d.yaml");
  const Config laser = c.Child("laser");
  EXPECT_DOUBLE_EQ(laser.GetDouble("fov_deg", 0.0), 180.0);
  laser.GetDouble("rate_hz", 0.0);
  try {
    c.CheckUnused();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "d.yaml:4: laser.fov_deg: duplicate key (first at line 2)");
  }
  try {
    laser.Keys();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "d.yaml:4: laser.fov_deg: duplicate key (first at line 2)");
  }
  // A whole section given twice, found by the top-level check of a stack file.
  const Config stack = Config::FromString("lcm: {}\nsegmenter: {}\nsegmenter: {}\n", "s.yaml");
  try {
    stack.CheckKeysAmong({"lcm", "segmenter"});
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:3: segmenter: duplicate key (first at line 2)");
  }
  // The same key in two different mappings is fine.
  const Config two = Config::FromString("a: {x: 1}\nb: {x: 2}\n", "t.yaml");
  two.Child("a").GetDouble("x", 0.0);
  two.Child("b").GetDouble("x", 0.0);
  EXPECT_NO_THROW(two.CheckUnused());
}

TEST(ConfigTest, CheckKeysAmong) {
  const Config c = Config::FromString("lcm: {}\nsegmentr: {}\n", "stack.yaml");
  EXPECT_THROW(c.CheckKeysAmong({"lcm", "segmenter"}), ConfigError);
  EXPECT_NO_THROW(c.CheckKeysAmong({"lcm", "segmentr"}));
}

TEST(ConfigTest, ChildOfWrongTypeIsAnError) {
  const Config c = Config::FromString("segmenter: 3\n", "s.yaml");
  EXPECT_THROW(c.Child("segmenter"), ConfigError);
  const Config empty = c.Child("absent");
  EXPECT_DOUBLE_EQ(empty.GetDouble("x", 4.0), 4.0);
}

}  // namespace
}  // namespace slammtt
