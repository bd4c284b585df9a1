// Reading a module's options schema (common/options_schema.h) from its configuration section.
//
// ConfigOptionReader sets every field whose key is present, in the unit the configuration
// writes it (degrees for an angle), keeps the default of every absent one, and throws
// ConfigError naming file, line and key for a value of the wrong type (Config's Get*) or outside
// its range:
//   config/robot.yaml:31: estimator.tracks_confirm_hits: must be in [1, 1000], got 0
// The caller then calls CheckUnused() on the section, so a key nobody reads is an error too.
// RejectRenamedKeys makes a key of an earlier version an error that names its new name, before
// CheckUnused() would call it merely unknown.
#pragma once

#include <string>
#include <vector>

#include "common/options_schema.h"
#include "runtime/config.h"

namespace slammtt {

class ConfigOptionReader : public OptionVisitor {
 public:
  explicit ConfigOptionReader(const Config& section) : section_(section) {}

 protected:
  void VisitDouble(const std::string& key, double* value, const OptionRange& range,
                   OptionUnit unit, const std::string& doc) override;
  void VisitInt(const std::string& key, int64_t* value, const OptionRange& range,
                const std::string& doc) override;
  void VisitBool(const std::string& key, bool* value, const std::string& doc) override;
  void VisitString(const std::string& key, std::string* value, const std::string& doc) override;
  void VisitChoice(const std::string& key, int* index, const std::vector<std::string>& names,
                   const std::string& doc) override;
  void VisitDoubleList(const std::string& key, const std::vector<double*>& values,
                       const std::vector<OptionUnit>& units, const std::string& layout,
                       const std::string& doc) override;

 private:
  Config section_;
};

// Throws ConfigError for a problem that a module's Check*Options found after reading (a
// condition between options, "reconnect_max_s must not be less than reconnect_initial_s"): at
// the line of the key it starts with when the section sets that key, at the section otherwise.
[[noreturn]] void FailOptionsProblem(const Config& section, const std::string& problem);

// A key an earlier version of a module's configuration used, and the key that replaced it.
struct RenamedKey {
  std::string old_key;
  std::string new_key;
};

// Throws ConfigError for the first key of `section` in `renamed`:
//   config/robot.yaml:31: estimator.gate_d1: renamed to gate_d1_chi2 (docs/estimator.md)
// `documented_in` says where the list of renamings is.
void RejectRenamedKeys(const Config& section, const std::vector<RenamedKey>& renamed,
                       const std::string& documented_in);

}  // namespace slammtt
