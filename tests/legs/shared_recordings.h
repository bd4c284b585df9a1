// Where the leg_tracker recordings are (../shared, or $SLAMMTT_SHARED_DIR) and whether the tests
// that import them can run here: they need the recordings and the Python venv's
// slammtt-import (scripts/python-env.sh). Shared by the real-data figures and the model's
// retraining.
#pragma once

#include <sys/stat.h>

#include <cstdlib>
#include <string>

namespace slammtt::testing {

inline std::string SharedReal() {
  const char* env = std::getenv("SLAMMTT_SHARED_DIR");
  const std::string shared = env != nullptr && *env != '\0'
                                 ? std::string(env)
                                 : std::string(SLAMMTT_SOURCE_DIR) + "/../shared";
  return shared + "/data/real";
}

inline bool Exists(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0;
}

// Why the tests cannot run here, or "" when they can.
inline std::string LegRecordingsUnavailable() {
  if (!Exists(SharedReal() + "/leg_tracker_training/positive_4_extracted.bag")) {
    return "the leg_tracker recordings are absent (" + SharedReal() +
           "; SLAMMTT_SHARED_DIR points elsewhere)";
  }
  if (!Exists(std::string(SLAMMTT_BIN_DIR) + "/../venv/bin/slammtt-import")) {
    return "no Python venv for slammtt-import (scripts/python-env.sh)";
  }
  return "";
}

}  // namespace slammtt::testing
