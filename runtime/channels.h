// Channel names of the stack. The defaults are the contract in the README's channel table; a
// process takes overrides from the `channels:` section of the stack configuration and from
// --channel KEY=NAME on its command line (the command line wins).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "runtime/config.h"

namespace slammtt {

class Channels {
 public:
  // Every known key with its default name: odometry -> ODOMETRY, laser_scan -> LASER_SCAN, ...
  Channels();

  // Applies a `channels:` section (unknown keys and unusable names are a ConfigError naming the
  // line).
  void ApplyConfig(const Config& section);
  // Applies "key=NAME" overrides (unknown keys, malformed text or unusable names throw
  // UsageError).
  void ApplyOverrides(const std::vector<std::string>& key_equals_name);

  // The channel for a key; std::out_of_range for a key that is not in the table (a bug).
  const std::string& Get(const std::string& key) const;
  const std::map<std::string, std::string>& All() const { return names_; }

  // Default names, for documentation and tests.
  static const std::map<std::string, std::string>& Defaults();

  // LCM 1.3.1 drops every message whose channel name is longer than this
  // (LCM_MAX_CHANNEL_NAME_LENGTH in lcm.h; lcm_udpm.c discards such packets on receipt).
  static constexpr size_t kMaxChannelNameBytes = 63;
  // Why `name` cannot be a channel name (empty, longer than kMaxChannelNameBytes, a control
  // character), or "" when it can.
  static std::string NameProblem(const std::string& name);

 private:
  std::map<std::string, std::string> names_;
};

}  // namespace slammtt
