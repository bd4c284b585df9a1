// The Java message types (build/share/java/slammtt_msgs.jar, cmake/SlammttLcmTypes.cmake): the
// jar holds a class per .lcm type, and a Java program (LogSummary.java) that reads a world log
// with LCM's Java log reader sees the very messages the C++ decoder sees. Skipped, with the
// reason, on a build configured without Java.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/ground_truth_t.hpp"
#include "slammtt_msgs/laser_scan_t.hpp"
#include "slammtt_msgs/odometry_t.hpp"
#include "tests/support/child_process.h"

namespace slammtt {
namespace {

namespace fs = std::filesystem;
using testing::ProcessResult;
using testing::RunProcess;
using testing::TempDir;

// Empty when the build was configured without Java (tests/java/CMakeLists.txt).
constexpr const char* kJava = SLAMMTT_JAVA_EXECUTABLE;
constexpr const char* kJar = SLAMMTT_JAR_EXECUTABLE;
constexpr const char* kLcmJar = SLAMMTT_LCM_JAR;
constexpr const char* kMessagesJar = SLAMMTT_MESSAGES_JAR;
constexpr const char* kTestClasses = SLAMMTT_JAVA_TEST_CLASSES;

#define SKIP_WITHOUT_JAVA()                                              \
  if (std::string(kJava).empty())                                        \
  GTEST_SKIP() << "configured without Java, missing:" SLAMMTT_JAVA_MISSING \
                  ": scripts/install-deps.sh installs it, then configure again"

// What LogSummary.java prints for one channel.
struct DecodedChannel {
  int64_t events = 0;
  int64_t first_utime = 0;
  int64_t last_utime = 0;
  double sum = 0;

  void Add(int64_t utime, double value) {
    if (events == 0) first_utime = utime;
    last_utime = utime;
    ++events;
    sum += value;
  }
};

// The same summary as LogSummary.java, from the C++ decoder (slammtt::Decode), adding the same
// fields in the same order.
std::map<std::string, DecodedChannel> CppSummary(const std::string& log_path) {
  std::map<std::string, DecodedChannel> channels;
  LogReader reader(log_path);
  while (auto event = reader.Next()) {
    const int size = static_cast<int>(event->data.size());
    if (event->channel == "LASER_SCAN") {
      slammtt_msgs::laser_scan_t scan{};
      if (!Decode(event->data.data(), size, &scan)) {
        ADD_FAILURE() << "LASER_SCAN event " << event->eventnum << " does not decode";
        continue;
      }
      double valid_ranges_m = 0;
      for (size_t i = 0; i < scan.range_m.size(); ++i) {
        if (scan.valid[i]) valid_ranges_m += static_cast<double>(scan.range_m[i]);
      }
      channels["LASER_SCAN"].Add(scan.utime, valid_ranges_m);
    } else if (event->channel == "ODOMETRY") {
      slammtt_msgs::odometry_t odometry{};
      if (!Decode(event->data.data(), size, &odometry)) {
        ADD_FAILURE() << "ODOMETRY event " << event->eventnum << " does not decode";
        continue;
      }
      channels["ODOMETRY"].Add(odometry.utime, odometry.x_m);
    } else if (event->channel == "GROUND_TRUTH") {
      slammtt_msgs::ground_truth_t truth{};
      if (!Decode(event->data.data(), size, &truth)) {
        ADD_FAILURE() << "GROUND_TRUTH event " << event->eventnum << " does not decode";
        continue;
      }
      channels["GROUND_TRUTH"].Add(truth.utime, truth.robot_x_m);
    }
  }
  return channels;
}

// Parses LogSummary.java's lines; a line that does not parse fails the test.
std::map<std::string, DecodedChannel> ParseJavaSummary(const std::string& text) {
  std::map<std::string, DecodedChannel> channels;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string channel, sum_text;
    DecodedChannel s;
    if (!(fields >> channel >> s.events >> s.first_utime >> s.last_utime >> sum_text)) {
      ADD_FAILURE() << "LogSummary printed an unexpected line: " << line;
      continue;
    }
    // Double.toString's shortest round-trip text: strtod gives back the very double.
    s.sum = std::stod(sum_text);
    channels[channel] = s;
  }
  return channels;
}

TEST(JavaTypesTest, JarHoldsOneClassPerLcmType) {
  SKIP_WITHOUT_JAVA();
  std::set<std::string> expected;
  for (const auto& entry : fs::directory_iterator(fs::path(SLAMMTT_SOURCE_DIR) / "lcmtypes")) {
    if (entry.path().extension() == ".lcm") {
      expected.insert("slammtt_msgs/" + entry.path().stem().string() + ".class");
    }
  }
  ASSERT_GE(expected.size(), 20u);
  TempDir dir("slammtt-java-types");
  const ProcessResult listing = RunProcess({kJar, "tf", kMessagesJar}, dir.path());
  ASSERT_EQ(listing.exit_code, 0) << listing.err;
  std::set<std::string> classes;
  std::istringstream lines(listing.out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.size() > 6 && line.compare(line.size() - 6, 6, ".class") == 0) classes.insert(line);
  }
  EXPECT_EQ(classes, expected);
}

TEST(JavaTypesTest, JavaReadsAWorldLogAsTheCppDecoderDoes) {
  SKIP_WITHOUT_JAVA();
  TempDir dir("slammtt-java-types");
  const std::string log = dir.File("world.lcm");
  const ProcessResult world =
      RunProcess({std::string(SLAMMTT_BIN_DIR) + "/slammtt-world", "--quiet", "--scenario",
                  "s1-crossing", "--seed", "1", "--duration", "2", "--output", "both", "--log",
                  log},
                 dir.path());
  ASSERT_EQ(world.exit_code, 0) << world.err;

  const std::string classpath = std::string(kLcmJar) + ":" + kMessagesJar + ":" + kTestClasses;
  const ProcessResult java = RunProcess({kJava, "-cp", classpath, "LogSummary", log}, dir.path());
  ASSERT_EQ(java.exit_code, 0) << java.err;
  const auto from_java = ParseJavaSummary(java.out);
  const auto from_cpp = CppSummary(log);

  for (const std::string channel : {"LASER_SCAN", "ODOMETRY", "GROUND_TRUTH"}) {
    SCOPED_TRACE(channel);
    ASSERT_EQ(from_java.count(channel), 1u) << java.out;
    ASSERT_EQ(from_cpp.count(channel), 1u);
    const DecodedChannel& j = from_java.at(channel);
    const DecodedChannel& c = from_cpp.at(channel);
    // 2 s of s1-crossing: laser and truth at 8 Hz, odometry at 20 Hz.
    EXPECT_GE(c.events, 16);
    EXPECT_EQ(j.events, c.events);
    EXPECT_EQ(j.first_utime, c.first_utime);
    EXPECT_EQ(j.last_utime, c.last_utime);
    EXPECT_NE(c.sum, 0.0);
    EXPECT_EQ(j.sum, c.sum);  // exactly: the same doubles added in the same order
  }
}

}  // namespace
}  // namespace slammtt
