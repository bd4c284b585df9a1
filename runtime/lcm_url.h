// LCM bus URLs, checked before LCM sees them. LCM 1.3.1 takes "PROVIDER://NETWORK?KEY=VALUE&..."
// (lcm.c, lcm_create) and is lenient where a robot must not be: "?ttl=abc" becomes ttl 0 with a
// warning, "?ttl=300" is stored in 8 bits and becomes 44, an unknown key such as "?tll=0" is
// printed and ignored, and a tcpq:// URL without its server leaves an object that later aborts
// the process. ParseLcmUrl accepts only what it can vouch for and says what is wrong in one line:
//
//   udpm://GROUP[:PORT][?ttl=N][&recv_buf_size=BYTES]   UDP multicast (lcm_udpm.c): GROUP an
//       IPv4 multicast address (224.0.0.0/4), PORT 1..65535 (default 7667), ttl 0..255
//       (default 0: nothing leaves the host), recv_buf_size 1..2^31-1; an empty NETWORK is
//       LCM's default 239.255.76.67:7667;
//   memq://                                             in-process queue (tests);
//   file://PATH[?mode=r|w|a][&speed=X][&start_timestamp=US]  LCM's log-file provider.
// Anything else (tcpq, mpudpm, an unknown provider, a key given twice) is an error.
#pragma once

#include <map>
#include <string>

namespace slammtt {

struct LcmUrl {
  std::string provider;                        // "udpm", "memq", "file"
  std::string network;                         // what is between "://" and "?"
  std::map<std::string, std::string> options;  // as written
  // udpm only.
  std::string group = "239.255.76.67";
  int port = 7667;
  int ttl = 0;
};

// Throws std::invalid_argument "LCM URL 'URL': <what is wrong>" (one line).
LcmUrl ParseLcmUrl(const std::string& url);

// True for a bus no packet of which leaves the host: memq, or udpm with ttl 0. (A udpm bus still
// receives unicast datagrams sent to any of the host's addresses on its port: LCM 1.3.1 binds
// its socket to 0.0.0.0; see docs/robot.md, "Who can drive the robot".)
bool IsLocalOnly(const LcmUrl& url);

}  // namespace slammtt
