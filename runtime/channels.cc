#include "runtime/channels.h"

#include "runtime/command_line.h"

namespace slammtt {

const std::map<std::string, std::string>& Channels::Defaults() {
  static const std::map<std::string, std::string> defaults = {
      {"odometry", "ODOMETRY"},
      {"velocity_command", "VELOCITY_COMMAND"},
      {"laser_scan", "LASER_SCAN"},
      {"features", "FEATURES"},
      {"pose", "POSE"},
      {"map", "MAP"},
      {"tracks", "TRACKS"},
      {"ground_truth", "GROUND_TRUTH"},
      {"stage_timing", "STAGE_TIMING"},
      {"lidar_status", "LIDAR_STATUS"},
      {"base_status", "BASE_STATUS"},
      {"estimator_status", "ESTIMATOR_STATUS"},
  };
  return defaults;
}

Channels::Channels() : names_(Defaults()) {}

void Channels::ApplyConfig(const Config& section) {
  for (const std::string& key : section.Keys()) {
    if (names_.count(key) == 0) section.FailKey(key, "unknown channel key");
    const std::string name = section.RequireString(key);
    if (name.empty()) section.FailKey(key, "channel name must not be empty");
    names_[key] = name;
  }
}

void Channels::ApplyOverrides(const std::vector<std::string>& key_equals_name) {
  for (const std::string& text : key_equals_name) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
      throw UsageError("--channel expects KEY=NAME, got '" + text + "'");
    }
    const std::string key = text.substr(0, eq);
    if (names_.count(key) == 0) throw UsageError("--channel: unknown channel key '" + key + "'");
    names_[key] = text.substr(eq + 1);
  }
}

const std::string& Channels::Get(const std::string& key) const { return names_.at(key); }

}  // namespace slammtt
