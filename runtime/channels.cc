#include "runtime/channels.h"

#include <lcm/lcm.h>

#include "runtime/command_line.h"

namespace slammtt {

static_assert(Channels::kMaxChannelNameBytes == LCM_MAX_CHANNEL_NAME_LENGTH,
              "the channel name limit is LCM's");

const std::map<std::string, std::string>& Channels::Defaults() {
  static const std::map<std::string, std::string> defaults = {
      {"odometry", "ODOMETRY"},
      {"velocity_command", "VELOCITY_COMMAND"},
      {"laser_scan", "LASER_SCAN"},
      {"laser_geometry", "LASER_GEOMETRY"},
      {"features", "FEATURES"},
      {"pose", "POSE"},
      {"map", "MAP"},
      {"tracks", "TRACKS"},
      {"ground_truth", "GROUND_TRUTH"},
      {"stage_timing", "STAGE_TIMING"},
      {"lidar_status", "LIDAR_STATUS"},
      {"base_status", "BASE_STATUS"},
      {"estimator_status", "ESTIMATOR_STATUS"},
      {"smoother_input", "SMOOTHER_INPUT"},
      {"smoothed_pose", "SMOOTHED_POSE"},
      {"smoothed_map", "SMOOTHED_MAP"},
      {"smoothed_trajectory", "SMOOTHED_TRAJECTORY"},
  };
  return defaults;
}

Channels::Channels() : names_(Defaults()) {}

std::string Channels::NameProblem(const std::string& name) {
  if (name.empty()) return "channel name must not be empty";
  if (name.size() > kMaxChannelNameBytes) {
    return "channel name of " + std::to_string(name.size()) + " bytes; LCM carries at most " +
           std::to_string(kMaxChannelNameBytes);
  }
  for (const char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      return "channel name with a control character";
    }
  }
  return "";
}

void Channels::ApplyConfig(const Config& section) {
  for (const std::string& key : section.Keys()) {
    if (names_.count(key) == 0) section.FailKey(key, "unknown channel key");
    const std::string name = section.RequireString(key);
    const std::string problem = NameProblem(name);
    if (!problem.empty()) section.FailKey(key, problem);
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
    const std::string problem = NameProblem(text.substr(eq + 1));
    if (!problem.empty()) throw UsageError("--channel " + key + ": " + problem);
    names_[key] = text.substr(eq + 1);
  }
}

const std::string& Channels::Get(const std::string& key) const { return names_.at(key); }

}  // namespace slammtt
