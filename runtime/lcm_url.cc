#include "runtime/lcm_url.h"

#include <arpa/inet.h>

#include <stdexcept>

#include "common/number_text.h"

namespace slammtt {
namespace {

[[noreturn]] void Fail(const std::string& url, const std::string& what) {
  throw std::invalid_argument("LCM URL '" + url + "': " + what);
}

// A whole number in [low, high] written with digits only (no sign, no blank).
bool WholeNumberIn(const std::string& text, int64_t low, int64_t high, int64_t* value) {
  if (text.empty() || text.size() > 19) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  const auto parsed = ParseWholeNumber(text);
  if (!parsed || *parsed < low || *parsed > high) return false;
  *value = *parsed;
  return true;
}

void CheckUdpm(const std::string& url, LcmUrl* parsed) {
  if (!parsed->network.empty()) {
    const size_t colon = parsed->network.find(':');
    parsed->group = parsed->network.substr(0, colon);
    if (colon != std::string::npos) {
      int64_t port = 0;
      if (!WholeNumberIn(parsed->network.substr(colon + 1), 1, 65535, &port)) {
        Fail(url, "port must be a whole number in 1..65535, got '" +
                      parsed->network.substr(colon + 1) + "'");
      }
      parsed->port = static_cast<int>(port);
    }
  }
  in_addr address{};
  if (inet_pton(AF_INET, parsed->group.c_str(), &address) != 1) {
    Fail(url, "'" + parsed->group + "' is not an IPv4 address");
  }
  if ((ntohl(address.s_addr) >> 28) != 0xE) {
    Fail(url, "'" + parsed->group + "' is not a multicast address (224.0.0.0/4)");
  }
  for (const auto& [key, value] : parsed->options) {
    int64_t number = 0;
    if (key == "ttl") {
      if (!WholeNumberIn(value, 0, 255, &number)) {
        Fail(url, "ttl must be a whole number in 0..255, got '" + value + "'");
      }
      parsed->ttl = static_cast<int>(number);
    } else if (key == "recv_buf_size") {
      if (!WholeNumberIn(value, 1, 2147483647, &number)) {
        Fail(url, "recv_buf_size must be a whole number of bytes in 1..2147483647, got '" +
                      value + "'");
      }
    } else {
      Fail(url, "unknown option '" + key + "' (udpm takes ttl and recv_buf_size)");
    }
  }
}

void CheckFile(const std::string& url, const LcmUrl& parsed) {
  if (parsed.network.empty()) Fail(url, "file:// needs a path");
  for (const auto& [key, value] : parsed.options) {
    if (key == "mode") {
      if (value != "r" && value != "w" && value != "a") {
        Fail(url, "mode must be r, w or a, got '" + value + "'");
      }
    } else if (key == "speed") {
      const auto speed = ParseFiniteDouble(value);
      if (!speed || *speed < 0.0) Fail(url, "speed must be a number >= 0, got '" + value + "'");
    } else if (key == "start_timestamp") {
      int64_t ignored = 0;
      if (!WholeNumberIn(value, 0, INT64_MAX, &ignored)) {
        Fail(url, "start_timestamp must be a whole number of microseconds, got '" + value + "'");
      }
    } else {
      Fail(url, "unknown option '" + key + "' (file takes mode, speed and start_timestamp)");
    }
  }
}

}  // namespace

LcmUrl ParseLcmUrl(const std::string& url) {
  LcmUrl parsed;
  const size_t scheme_end = url.find("://");
  if (scheme_end == std::string::npos || scheme_end == 0) {
    Fail(url, "expected PROVIDER://NETWORK[?KEY=VALUE&...], e.g. udpm://239.255.76.67:7667?ttl=0");
  }
  parsed.provider = url.substr(0, scheme_end);
  const std::string rest = url.substr(scheme_end + 3);
  const size_t query = rest.find('?');
  parsed.network = rest.substr(0, query);
  if (query != std::string::npos) {
    const std::string options = rest.substr(query + 1);
    size_t begin = 0;
    while (begin <= options.size()) {
      const size_t end = std::min(options.find('&', begin), options.size());
      const std::string item = options.substr(begin, end - begin);
      const size_t equals = item.find('=');
      if (item.empty() || equals == std::string::npos || equals == 0) {
        Fail(url, "options must be KEY=VALUE separated by '&', got '" + item + "'");
      }
      const std::string key = item.substr(0, equals);
      if (!parsed.options.emplace(key, item.substr(equals + 1)).second) {
        Fail(url, "option '" + key + "' given twice");
      }
      begin = end + 1;
    }
  }
  if (parsed.provider == "udpm") {
    CheckUdpm(url, &parsed);
  } else if (parsed.provider == "memq") {
    if (!parsed.network.empty() || !parsed.options.empty()) Fail(url, "memq:// takes nothing");
  } else if (parsed.provider == "file") {
    CheckFile(url, parsed);
  } else if (parsed.provider == "tcpq" || parsed.provider == "mpudpm") {
    Fail(url, "the " + parsed.provider +
                  " provider is not supported (with LCM 1.3.1 a tcpq bus whose server is "
                  "missing aborts the process later); use udpm://");
  } else {
    Fail(url, "unknown provider '" + parsed.provider + "' (udpm, memq or file)");
  }
  return parsed;
}

bool IsLocalOnly(const LcmUrl& url) {
  return url.provider == "memq" || (url.provider == "udpm" && url.ttl == 0);
}

}  // namespace slammtt
