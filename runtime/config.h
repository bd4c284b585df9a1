// The one configuration format of the stack: YAML files read through Config.
//
// A whole-stack file has one section per process (see config/robot.yaml); scenario files of the
// synthetic world use the same reader. Reading a key marks it used, and CheckUnused() throws for
// every key nobody read, so a typo is an error instead of a silently ignored setting (the
// Cartographer rule); so is a key given twice in one mapping (YAML parsers keep the first and
// drop the second silently). Every error names the file, the line and the key path, in one line:
//   config/robot.yaml:12: segmenter.lambda_deg: expected a number, got "twenty"
//
// Config is a cheap handle: copies share the file and the record of used keys.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace slammtt {

// Bad configuration or scenario input. what() is one line that names file, line and key.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Config {
 public:
  // An empty mapping (every Get returns its default).
  Config();
  // Parses a YAML file; throws ConfigError "PATH: ..." when it is missing, not a regular file
  // (a directory, /dev/zero, a FIFO), larger than 16 MiB or not valid YAML, or when its top
  // level is not a mapping.
  static Config LoadFile(const std::string& path);
  // Parses YAML text; `source` names it in error messages.
  static Config FromString(const std::string& yaml_text, const std::string& source = "<string>");

  bool Has(const std::string& key) const;
  bool IsMap() const;
  bool IsSequence() const;
  bool IsScalar() const;
  // Keys of a mapping in file order (does not mark them used); ConfigError for a key that is
  // not plain text or that appears twice.
  std::vector<std::string> Keys() const;
  // Number of elements of a sequence (0 for anything else).
  size_t Size() const;

  // Optional scalar keys: the default when the key is absent or null; ConfigError when present
  // with the wrong type. Integers accept only whole numbers; doubles reject NaN and infinities.
  double GetDouble(const std::string& key, double fallback) const;
  int64_t GetInt(const std::string& key, int64_t fallback) const;
  bool GetBool(const std::string& key, bool fallback) const;
  std::string GetString(const std::string& key, const std::string& fallback) const;
  std::vector<double> GetDoubles(const std::string& key, const std::vector<double>& fallback) const;

  // Required scalar keys: ConfigError "missing key" when absent.
  double RequireDouble(const std::string& key) const;
  int64_t RequireInt(const std::string& key) const;
  bool RequireBool(const std::string& key) const;
  std::string RequireString(const std::string& key) const;
  std::vector<double> RequireDoubles(const std::string& key) const;

  // The value of this node itself (for sequence elements).
  double AsDouble() const;
  int64_t AsInt() const;
  std::string AsString() const;
  std::vector<double> AsDoubles() const;

  // A nested mapping; an absent key gives an empty mapping, so optional sections read their
  // defaults. ConfigError if present but not a mapping.
  Config Child(const std::string& key) const;
  // A nested mapping that must be present.
  Config RequireChild(const std::string& key) const;
  // Elements of a sequence key (empty when absent). ConfigError if present but not a sequence.
  std::vector<Config> Items(const std::string& key) const;
  // Elements of this node when it is itself a sequence.
  std::vector<Config> Elements() const;

  // Throws ConfigError for the first key under this node (recursively) that was never read or
  // that appears twice in its mapping.
  void CheckUnused() const;
  // Throws ConfigError when this mapping has a key outside `allowed` (marks none used).
  void CheckKeysAmong(const std::vector<std::string>& allowed) const;

  // Throws ConfigError "<file>:<line>: <path>: <message>" for this node, or for `key` under it.
  [[noreturn]] void Fail(const std::string& message) const;
  [[noreturn]] void FailKey(const std::string& key, const std::string& message) const;

  // "file:line" of this node and its dotted key path ("objects[2].radius_m").
  std::string Where() const;
  const std::string& Path() const { return path_; }
  const std::string& Source() const;

 private:
  struct Impl;
  struct Shared;
  Config(std::shared_ptr<const Impl> impl, std::shared_ptr<Shared> shared, std::string path);
  Config Lookup(const std::string& key) const;  // marks used; null node when absent
  std::string ChildPath(const std::string& key) const;
  std::string LineOf(const std::string& key) const;

  std::shared_ptr<const Impl> impl_;
  std::shared_ptr<Shared> shared_;
  std::string path_;
};

}  // namespace slammtt
