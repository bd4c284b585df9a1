// The options a pure class keeps, after its module's check: every constructor that validates
// its options (docs/DEVELOPING.md, "Options: one schema per module") initialises its copy with
//
//   options_(CheckedOptions(options, &CheckEstimatorOptions, "estimator options"))
//
// so that a bad option is a std::invalid_argument "estimator options: PROBLEM" (the check
// names the key) before anything is built. Standard library only, like the rest of common/.
#pragma once

#include <stdexcept>
#include <string>

namespace slammtt {

// `options` as given when `check` finds nothing; else std::invalid_argument "WHAT: PROBLEM".
template <typename Options>
const Options& CheckedOptions(const Options& options,
                              std::string (*check)(const Options& options), const char* what) {
  const std::string problem = check(options);
  if (!problem.empty()) throw std::invalid_argument(std::string(what) + ": " + problem);
  return options;
}

}  // namespace slammtt
