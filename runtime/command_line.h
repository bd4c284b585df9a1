// Command-line options for every slammtt program: GNU-style long options (--name VALUE or
// --name=VALUE), short aliases, positional arguments, a generated --help and --version.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace slammtt {

// A command line that cannot be understood. ProcessMain exits with status 2 on it.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The project's version (CMake's PROJECT_VERSION, as the Python tools' slammtt.__version__).
const char* SlammttVersion();

class CommandLine {
 public:
  // `usage` is the synopsis after the program name ("[options] IN.lcm -o OUT.lcm").
  CommandLine(std::string program, std::string usage, std::string description);

  // --name (no value). `short_name` is 0 or a letter for "-x".
  void AddFlag(const std::string& name, const std::string& help, char short_name = 0);
  // --name VALUE, at most once.
  void AddOption(const std::string& name, const std::string& value_name, const std::string& help,
                 char short_name = 0);
  // --name VALUE, any number of times.
  void AddRepeatedOption(const std::string& name, const std::string& value_name,
                         const std::string& help);
  // Positional arguments, in order; the last may be optional.
  void AddPositional(const std::string& name, const std::string& help, bool required = true);

  // Parses argv. Returns false when --help or --version was asked for (the help, or the line
  // "PROGRAM VERSION", is already printed on stdout: the caller exits 0). Throws UsageError for
  // anything it does not understand.
  bool Parse(int argc, const char* const* argv);

  bool Flag(const std::string& name) const;
  std::optional<std::string> Value(const std::string& name) const;
  std::string ValueOr(const std::string& name, const std::string& fallback) const;
  std::vector<std::string> Values(const std::string& name) const;
  std::optional<std::string> Positional(const std::string& name) const;

  // Numeric option values; UsageError naming the option when the text is not a number.
  std::optional<double> DoubleValue(const std::string& name) const;
  std::optional<int64_t> IntValue(const std::string& name) const;

  std::string Help() const;
  const std::string& program() const { return program_; }

 private:
  struct Spec {
    std::string name;
    std::string value_name;  // empty for a flag
    std::string help;
    char short_name = 0;
    bool repeated = false;
  };
  struct PositionalSpec {
    std::string name;
    std::string help;
    bool required = true;
  };
  const Spec* Find(const std::string& name) const;
  const Spec* FindShort(char c) const;

  std::string program_;
  std::string usage_;
  std::string description_;
  std::vector<Spec> specs_;
  std::vector<PositionalSpec> positional_specs_;
  std::map<std::string, std::vector<std::string>> values_;
  std::map<std::string, std::string> positionals_;
};

}  // namespace slammtt
