#include "runtime/command_line.h"

#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "common/number_text.h"

namespace slammtt {

const char* SlammttVersion() { return SLAMMTT_VERSION; }

CommandLine::CommandLine(std::string program, std::string usage, std::string description)
    : program_(std::move(program)), usage_(std::move(usage)), description_(std::move(description)) {
  AddFlag("help", "print this help and exit", 'h');
  AddFlag("version", "print the program's name and version and exit");
}

void CommandLine::AddFlag(const std::string& name, const std::string& help, char short_name) {
  specs_.push_back({name, "", help, short_name, false});
}

void CommandLine::AddOption(const std::string& name, const std::string& value_name,
                            const std::string& help, char short_name) {
  specs_.push_back({name, value_name, help, short_name, false});
}

void CommandLine::AddRepeatedOption(const std::string& name, const std::string& value_name,
                                    const std::string& help) {
  specs_.push_back({name, value_name, help, 0, true});
}

void CommandLine::AddPositional(const std::string& name, const std::string& help, bool required) {
  positional_specs_.push_back({name, help, required});
}

const CommandLine::Spec* CommandLine::Find(const std::string& name) const {
  for (const Spec& s : specs_) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const CommandLine::Spec* CommandLine::FindShort(char c) const {
  for (const Spec& s : specs_) {
    if (s.short_name != 0 && s.short_name == c) return &s;
  }
  return nullptr;
}

bool CommandLine::Parse(int argc, const char* const* argv) {
  values_.clear();
  positionals_.clear();
  size_t next_positional = 0;
  bool options_done = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const Spec* spec = nullptr;
    std::optional<std::string> inline_value;
    if (!options_done && arg == "--") {
      options_done = true;
      continue;
    }
    if (!options_done && arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      std::string name = arg.substr(2);
      const size_t eq = name.find('=');
      if (eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      spec = Find(name);
      if (spec == nullptr) throw UsageError("unknown option --" + name + " (see --help)");
    } else if (!options_done && arg.size() == 2 && arg[0] == '-' && arg[1] != '-') {
      spec = FindShort(arg[1]);
      if (spec == nullptr) throw UsageError("unknown option " + arg + " (see --help)");
    }
    if (spec == nullptr) {
      if (next_positional >= positional_specs_.size()) {
        throw UsageError("unexpected argument '" + arg + "' (see --help)");
      }
      positionals_[positional_specs_[next_positional++].name] = arg;
      continue;
    }
    if (spec->value_name.empty()) {
      if (inline_value) throw UsageError("option --" + spec->name + " takes no value");
      values_[spec->name].push_back("1");
      continue;
    }
    std::string value;
    if (inline_value) {
      value = *inline_value;
    } else {
      if (i + 1 >= argc) throw UsageError("option --" + spec->name + " needs a value");
      value = argv[++i];
    }
    auto& list = values_[spec->name];
    if (!spec->repeated && !list.empty()) {
      throw UsageError("option --" + spec->name + " given more than once");
    }
    list.push_back(value);
  }
  if (Flag("help")) {
    std::cout << Help();
    return false;
  }
  if (Flag("version")) {
    std::cout << program_ << " " << SlammttVersion() << "\n";
    return false;
  }
  for (size_t k = next_positional; k < positional_specs_.size(); ++k) {
    if (positional_specs_[k].required) {
      throw UsageError("missing argument " + positional_specs_[k].name + " (see --help)");
    }
  }
  return true;
}

bool CommandLine::Flag(const std::string& name) const { return values_.count(name) > 0; }

std::optional<std::string> CommandLine::Value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

std::string CommandLine::ValueOr(const std::string& name, const std::string& fallback) const {
  return Value(name).value_or(fallback);
}

std::vector<std::string> CommandLine::Values(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::optional<std::string> CommandLine::Positional(const std::string& name) const {
  auto it = positionals_.find(name);
  if (it == positionals_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> CommandLine::DoubleValue(const std::string& name) const {
  const auto text = Value(name);
  if (!text) return std::nullopt;
  const std::optional<double> value = ParseFiniteDouble(*text);
  if (!value) throw UsageError("option --" + name + ": expected a number, got '" + *text + "'");
  return value;
}

std::optional<int64_t> CommandLine::IntValue(const std::string& name) const {
  const auto text = Value(name);
  if (!text) return std::nullopt;
  const std::optional<int64_t> value = ParseWholeNumber(*text);
  if (!value) {
    throw UsageError("option --" + name + ": expected a whole number, got '" + *text + "'");
  }
  return value;
}

std::string CommandLine::Help() const {
  std::ostringstream out;
  out << "usage: " << program_ << " " << usage_ << "\n\n" << description_ << "\n";
  if (!positional_specs_.empty()) {
    out << "\narguments:\n";
    for (const PositionalSpec& p : positional_specs_) {
      out << "  " << p.name << (p.required ? "" : " (optional)") << "\n      " << p.help << "\n";
    }
  }
  out << "\noptions:\n";
  for (const Spec& s : specs_) {
    out << "  ";
    if (s.short_name != 0) out << "-" << s.short_name << ", ";
    out << "--" << s.name;
    if (!s.value_name.empty()) out << " " << s.value_name;
    if (s.repeated) out << " (repeatable)";
    out << "\n      " << s.help << "\n";
  }
  return out.str();
}

}  // namespace slammtt
