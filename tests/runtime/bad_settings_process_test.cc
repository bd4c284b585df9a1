// Every program of the stack meets a bad setting or a file that is no log with one line on
// stderr and a non-zero exit status: never a hang, an abort or a silent start (issue 15 item 5;
// the "before" of each case is in the commit that added it). Runs in a network namespace of its
// own (NETNS): a URL that LCM would take must not reach a real network.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/child_process.h"

namespace slammtt {
namespace {

using testing::ProcessResult;
using testing::RunProcess;

std::string Bin(const std::string& program) { return std::string(SLAMMTT_BIN_DIR) + "/" + program; }

struct Case {
  std::vector<std::string> argv;
  int exit_code;
  std::string says;
};

class BadSettingsTest : public ::testing::Test {
 protected:
  std::string File(const std::string& name, const std::string& text) {
    const std::string path = dir_.File(name);
    std::ofstream(path) << text;
    return path;
  }
  void Expect(const Case& c) {
    std::string command;
    for (const std::string& arg : c.argv) command += (command.empty() ? "" : " ") + arg;
    const ProcessResult result = RunProcess(c.argv, dir_.path(), 20000);
    EXPECT_EQ(result.exit_code, c.exit_code) << command << "\n" << result.err;
    EXPECT_NE(result.err.find(c.says), std::string::npos) << command << "\n" << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1)
        << command << "\n" << result.err;
  }
  testing::TempDir dir_;
};

TEST_F(BadSettingsTest, BusUrlsLcmWouldMisreadAreOneLine) {
  const std::string segmenter = Bin("slammtt-segmenter");
  for (const Case& c : std::vector<Case>{
           {{segmenter, "--lcm-url", "tcpq://127.0.0.1:7700"}, 1,
            "the tcpq provider is not supported"},
           {{segmenter, "--lcm-url", "udpm://239.255.76.67:7667?ttl=abc"}, 1,
            "ttl must be a whole number in 0..255, got 'abc'"},
           {{segmenter, "--lcm-url", "udpm://239.255.76.67:7667?ttl=300"}, 1, "got '300'"},
           {{segmenter, "--lcm-url", "udpm://239.255.76.67:7667?tll=0"}, 1, "unknown option 'tll'"},
           {{Bin("slammtt-p3dx"), "--port", "tcp://127.0.0.1:9", "--lcm-url",
             "udpm://10.1.1.1:7667"},
            1, "not a multicast address"},
       }) {
    Expect(c);
  }
}

TEST_F(BadSettingsTest, ChannelNamesLcmCannotCarryAreOneLine) {
  Expect({{Bin("slammtt-segmenter"), "--channel", "features=" + std::string(64, 'F')}, 2,
          "channel name of 64 bytes; LCM carries at most 63"});
  Expect({{Bin("slammtt-estimator"), "--config",
           File("channels.yaml", "channels:\n  pose: " + std::string(100, 'P') + "\n")},
          1, "channels.pose: channel name of 100 bytes"});
}

TEST_F(BadSettingsTest, AConfigurationThatIsNoFileIsOneLine) {
  for (const std::string& path : {dir_.path(), std::string("/dev/zero")}) {
    Expect({{Bin("slammtt-segmenter"), "--config", path}, 1, path + ": not a regular file"});
  }
}

TEST_F(BadSettingsTest, AbsurdOptionValuesAreOneLine) {
  Expect({{Bin("slammtt-rplidar"), "--config",
           File("angle.yaml", "rplidar:\n  port: tcp://127.0.0.1:9\n  angle_offset_deg: 1e300\n")},
          1, "rplidar.angle_offset_deg: must be in [-360, 360], got 1e+300"});
  Expect({{Bin("slammtt-estimator"), "--config",
           File("objects.yaml", "estimator:\n  max_objects: 0\n")},
          1, "estimator.max_objects"});
}

TEST_F(BadSettingsTest, ALogThatIsNoFileIsOneLineForEveryTool) {
  for (const std::string& log : {dir_.path(), std::string("/dev/zero")}) {
    const std::string says = log + ": not a log file (not a regular file)";
    Expect({{Bin("slammtt-replay"), log, "-o", dir_.File("out.lcm")}, 1, says});
    Expect({{Bin("slammtt-eval"), log, "--json", dir_.File("report.json")}, 1, says});
    Expect({{Bin("slammtt-timing"), log}, 1, says});
    Expect({{Bin("slammtt-timing"), "--json", log}, 1, says});
  }
  struct stat info {};
  EXPECT_NE(stat(dir_.File("out.lcm").c_str(), &info), 0);
  EXPECT_NE(stat(dir_.File("report.json").c_str(), &info), 0);
}

}  // namespace
}  // namespace slammtt
