#include "runtime/lcm_url.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "runtime/lcm_io.h"

namespace slammtt {
namespace {

std::string Problem(const std::string& url) {
  try {
    ParseLcmUrl(url);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(LcmUrlParseTest, AcceptsTheBusesTheStackUses) {
  const LcmUrl shipped = ParseLcmUrl(kDefaultLcmUrl);
  EXPECT_EQ(shipped.provider, "udpm");
  EXPECT_EQ(shipped.group, "239.255.76.67");
  EXPECT_EQ(shipped.port, 7667);
  EXPECT_EQ(shipped.ttl, 0);
  EXPECT_TRUE(IsLocalOnly(shipped));
  const LcmUrl lan = ParseLcmUrl("udpm://239.255.76.68:7700?ttl=1&recv_buf_size=2097152");
  EXPECT_EQ(lan.group, "239.255.76.68");
  EXPECT_EQ(lan.port, 7700);
  EXPECT_EQ(lan.ttl, 1);
  EXPECT_FALSE(IsLocalOnly(lan));
  EXPECT_EQ(ParseLcmUrl("udpm://").port, 7667);          // LCM's defaults
  EXPECT_EQ(ParseLcmUrl("udpm://239.1.2.3").port, 7667);
  EXPECT_EQ(ParseLcmUrl("udpm://239.1.2.3?ttl=255").ttl, 255);
  EXPECT_TRUE(IsLocalOnly(ParseLcmUrl("memq://")));
  EXPECT_FALSE(IsLocalOnly(ParseLcmUrl("file:///tmp/x.lcm?mode=w")));
  EXPECT_EQ(ParseLcmUrl("file:///tmp/x.lcm?speed=2.5&start_timestamp=0").provider, "file");
}

// Each of these LCM 1.3.1 takes without an error (ttl=abc is ttl 0, ttl=300 is 44, tll=0 is
// ignored, tcpq:// without its server aborts the process later): each is one line here.
TEST(LcmUrlParseTest, RejectsWhatLcmWouldMisreadWithOneLine) {
  const struct {
    const char* url;
    const char* says;
  } cases[] = {
      {"udpm://239.255.76.67:7667?ttl=abc", "ttl must be a whole number in 0..255, got 'abc'"},
      {"udpm://239.255.76.67:7667?ttl=300", "ttl must be a whole number in 0..255, got '300'"},
      {"udpm://239.255.76.67:7667?ttl=-1", "ttl must be a whole number in 0..255"},
      {"udpm://239.255.76.67:7667?ttl=", "ttl must be a whole number"},
      {"udpm://239.255.76.67:7667?ttl=0x1", "ttl must be a whole number"},
      {"udpm://239.255.76.67:7667?tll=0",
       "unknown option 'tll' (udpm takes ttl and recv_buf_size)"},
      {"udpm://239.255.76.67:7667?ttl=0&ttl=1", "option 'ttl' given twice"},
      {"udpm://239.255.76.67:7667?ttl", "options must be KEY=VALUE"},
      {"udpm://239.255.76.67:7667?ttl=0&", "options must be KEY=VALUE"},
      {"udpm://239.255.76.67:7667?recv_buf_size=0", "recv_buf_size must be a whole number"},
      {"udpm://239.255.76.67:99999", "port must be a whole number in 1..65535, got '99999'"},
      {"udpm://239.255.76.67:", "port must be a whole number"},
      {"udpm://239.255.76.67:76x", "port must be a whole number"},
      {"udpm://10.0.0.5:7667", "'10.0.0.5' is not a multicast address (224.0.0.0/4)"},
      {"udpm://robot.local:7667", "'robot.local' is not an IPv4 address"},
      {"tcpq://127.0.0.1:7700", "the tcpq provider is not supported"},
      {"mpudpm://239.255.76.67:7667", "the mpudpm provider is not supported"},
      {"foo://x", "unknown provider 'foo' (udpm, memq or file)"},
      {"239.255.76.67:7667", "expected PROVIDER://NETWORK"},
      {"", "expected PROVIDER://NETWORK"},
      {"memq://x", "memq:// takes nothing"},
      {"file://", "file:// needs a path"},
      {"file:///x.lcm?mode=rw", "mode must be r, w or a"},
      {"file:///x.lcm?speed=-1", "speed must be a number >= 0"},
  };
  for (const auto& c : cases) {
    const std::string problem = Problem(c.url);
    EXPECT_NE(problem.find(c.says), std::string::npos) << c.url << ": " << problem;
    EXPECT_EQ(problem.rfind(std::string("LCM URL '") + c.url + "': ", 0), 0u) << problem;
    EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
  }
}

TEST(LcmUrlParseTest, OpenLcmRefusesABadUrlBeforeLcmSeesIt) {
  try {
    OpenLcm("udpm://239.255.76.67:7667?tll=0");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown option 'tll'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OpenLcm("tcpq://127.0.0.1:7700"), std::runtime_error);
  EXPECT_NE(OpenLcm("memq://"), nullptr);
}

}  // namespace
}  // namespace slammtt
