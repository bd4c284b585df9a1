#include "runtime/command_line_options.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace slammtt {
namespace {

std::string Quoted(const std::string& text) { return text.empty() ? "\"\"" : text; }

}  // namespace

CommandLineOptions::CommandLineOptions(std::vector<std::string> keys, std::string section)
    : keys_(std::move(keys)), section_(std::move(section)) {}

std::string CommandLineOptions::FlagOf(const std::string& key) {
  std::string name = key;
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

bool CommandLineOptions::Selected(const std::string& key) const {
  return std::find(keys_.begin(), keys_.end(), key) != keys_.end();
}

void CommandLineOptions::DeclareVisitor::Declare(const std::string& key,
                                                 const std::string& value_name,
                                                 const std::string& doc,
                                                 const std::string& default_text,
                                                 const std::string& valid) {
  if (!owner_->Selected(key)) return;
  command_line_->AddOption(FlagOf(key).substr(2), value_name,
                           doc + " (" + owner_->section_ + "." + key + ", default " +
                               default_text + (valid.empty() ? "" : ", " + valid) + ")");
}

void CommandLineOptions::DeclareVisitor::VisitDouble(const std::string& key, double* value,
                                                     const OptionRange& range, OptionUnit unit,
                                                     const std::string& doc) {
  Declare(key, "X", doc, OptionRange::Number(ToConfigUnit(*value, unit)), range.Text());
}

void CommandLineOptions::DeclareVisitor::VisitInt(const std::string& key, int64_t* value,
                                                  const OptionRange& range,
                                                  const std::string& doc) {
  Declare(key, "N", doc, std::to_string(*value), range.Text());
}

void CommandLineOptions::DeclareVisitor::VisitBool(const std::string& key, bool* value,
                                                   const std::string& doc) {
  Declare(key, "BOOL", doc, *value ? "true" : "false", "true, false");
}

void CommandLineOptions::DeclareVisitor::VisitString(const std::string& key,
                                                     std::string* value,
                                                     const std::string& doc) {
  Declare(key, "TEXT", doc, Quoted(*value), "");
}

void CommandLineOptions::DeclareVisitor::VisitChoice(const std::string& key, int* index,
                                                     const std::vector<std::string>& names,
                                                     const std::string& doc) {
  std::string all;
  for (const std::string& name : names) all += (all.empty() ? "" : ", ") + name;
  Declare(key, "NAME", doc, names[static_cast<size_t>(*index)], all);
}

void CommandLineOptions::DeclareVisitor::VisitDoubleList(const std::string& key,
                                                         const std::vector<double*>&,
                                                         const std::vector<OptionUnit>&,
                                                         const std::string& layout,
                                                         const std::string&) {
  // A list is a configuration key only (no program offers one on its command line).
  if (owner_->Selected(key)) {
    throw std::logic_error(key + " " + layout + ": a list cannot be a command-line option");
  }
}

void CommandLineOptions::ApplyVisitor::VisitDouble(const std::string& key, double* value,
                                                   const OptionRange& range, OptionUnit unit,
                                                   const std::string&) {
  if (!owner_->Selected(key)) return;
  const std::string flag = FlagOf(key);
  const std::optional<double> given = command_line_.DoubleValue(flag.substr(2));
  if (!given) return;
  if (!range.Contains(*given)) {
    throw UsageError(flag + ": must be " + range.Requirement() + ", got " +
                     OptionRange::Number(*given));
  }
  *value = FromConfigUnit(*given, unit);
}

void CommandLineOptions::ApplyVisitor::VisitInt(const std::string& key, int64_t* value,
                                                const OptionRange& range, const std::string&) {
  if (!owner_->Selected(key)) return;
  const std::string flag = FlagOf(key);
  const std::optional<int64_t> given = command_line_.IntValue(flag.substr(2));
  if (!given) return;
  if (!range.Contains(static_cast<double>(*given))) {
    throw UsageError(flag + ": must be " + range.Requirement() + ", got " +
                     std::to_string(*given));
  }
  *value = *given;
}

void CommandLineOptions::ApplyVisitor::VisitBool(const std::string& key, bool* value,
                                                 const std::string&) {
  if (!owner_->Selected(key)) return;
  const std::string flag = FlagOf(key);
  const std::optional<std::string> given = command_line_.Value(flag.substr(2));
  if (!given) return;
  if (*given != "true" && *given != "false") {
    throw UsageError(flag + ": expected true or false, got '" + *given + "'");
  }
  *value = *given == "true";
}

void CommandLineOptions::ApplyVisitor::VisitString(const std::string& key, std::string* value,
                                                   const std::string&) {
  if (!owner_->Selected(key)) return;
  if (const auto given = command_line_.Value(FlagOf(key).substr(2))) *value = *given;
}

void CommandLineOptions::ApplyVisitor::VisitChoice(const std::string& key, int* index,
                                                   const std::vector<std::string>& names,
                                                   const std::string&) {
  if (!owner_->Selected(key)) return;
  const std::string flag = FlagOf(key);
  const std::optional<std::string> given = command_line_.Value(flag.substr(2));
  if (!given) return;
  std::string expected;
  for (size_t k = 0; k < names.size(); ++k) {
    if (names[k] == *given) {
      *index = static_cast<int>(k);
      return;
    }
    expected += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  throw UsageError(flag + ": expected " + expected + ", got '" + *given + "'");
}

void CommandLineOptions::ApplyVisitor::VisitDoubleList(const std::string&,
                                                       const std::vector<double*>&,
                                                       const std::vector<OptionUnit>&,
                                                       const std::string&,
                                                       const std::string&) {}

}  // namespace slammtt
