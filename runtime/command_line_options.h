// Options of a module's schema (common/options_schema.h) that the command line may set too,
// after the configuration (the command line wins): the option --KEY, with the key's '_' written
// '-' (p3dx.max_linear_mps is --max-linear-mps), takes the value in the unit of the
// configuration, is held to the schema's range, and its help is the schema's one line with the
// section key and the default. Only the keys a program names get an option.
//
//   CommandLineOptions flags({"port", "baud"}, "rplidar");
//   flags.Declare(&command_line, VisitRplidarDriverOptions);   // before Parse
//   flags.Apply(command_line, VisitRplidarDriverOptions, &options);  // after the config
//
// A value out of range, or not a number, is a UsageError naming the option:
//   --max-linear-mps: must be in (0, 2], got 3
#pragma once

#include <string>
#include <vector>

#include "common/options_schema.h"
#include "runtime/command_line.h"

namespace slammtt {

class CommandLineOptions {
 public:
  // `keys`: the configuration keys that get an option; `section`: their section, for the help.
  CommandLineOptions(std::vector<std::string> keys, std::string section);

  // Declares --KEY for each key, with the schema's doc, default and range as help.
  template <typename Options>
  void Declare(CommandLine* command_line, void (*visit)(OptionVisitor*, Options*)) const;

  // Sets every field whose option is on the command line. UsageError naming the option for a
  // value that is not a number, not one of the choices or out of range.
  template <typename Options>
  void Apply(const CommandLine& command_line, void (*visit)(OptionVisitor*, Options*),
             Options* options) const;

  // "--max-linear-mps" for "max_linear_mps".
  static std::string FlagOf(const std::string& key);

 private:
  class DeclareVisitor;
  class ApplyVisitor;
  bool Selected(const std::string& key) const;

  std::vector<std::string> keys_;
  std::string section_;
};

// The visitor that declares the options (help: doc, "SECTION.KEY", default, valid values).
class CommandLineOptions::DeclareVisitor : public OptionVisitor {
 public:
  DeclareVisitor(const CommandLineOptions* owner, CommandLine* command_line)
      : owner_(owner), command_line_(command_line) {}

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
  void Declare(const std::string& key, const std::string& value_name, const std::string& doc,
               const std::string& default_text, const std::string& valid);
  const CommandLineOptions* owner_;
  CommandLine* command_line_;
};

// The visitor that reads the options' values.
class CommandLineOptions::ApplyVisitor : public OptionVisitor {
 public:
  ApplyVisitor(const CommandLineOptions* owner, const CommandLine& command_line)
      : owner_(owner), command_line_(command_line) {}

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
  const CommandLineOptions* owner_;
  const CommandLine& command_line_;
};

template <typename Options>
void CommandLineOptions::Declare(CommandLine* command_line,
                                 void (*visit)(OptionVisitor*, Options*)) const {
  Options defaults;
  DeclareVisitor declare(this, command_line);
  visit(&declare, &defaults);
}

template <typename Options>
void CommandLineOptions::Apply(const CommandLine& command_line,
                               void (*visit)(OptionVisitor*, Options*), Options* options) const {
  ApplyVisitor apply(this, command_line);
  visit(&apply, options);
}

}  // namespace slammtt
