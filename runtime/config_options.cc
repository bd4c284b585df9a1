#include "runtime/config_options.h"

namespace slammtt {

void ConfigOptionReader::VisitDouble(const std::string& key, double* value,
                                     const OptionRange& range, OptionUnit unit,
                                     const std::string&) {
  if (!section_.Has(key)) return;
  const double config_value = section_.GetDouble(key, ToConfigUnit(*value, unit));
  if (!range.Contains(config_value)) {
    section_.FailKey(key, "must be " + range.Requirement() + ", got " +
                              OptionRange::Number(config_value));
  }
  *value = FromConfigUnit(config_value, unit);
}

void ConfigOptionReader::VisitInt(const std::string& key, int64_t* value,
                                  const OptionRange& range, const std::string&) {
  if (!section_.Has(key)) return;
  const int64_t config_value = section_.GetInt(key, *value);
  if (!range.Contains(static_cast<double>(config_value))) {
    section_.FailKey(key, "must be " + range.Requirement() + ", got " +
                              std::to_string(config_value));
  }
  *value = config_value;
}

void ConfigOptionReader::VisitBool(const std::string& key, bool* value, const std::string&) {
  *value = section_.GetBool(key, *value);
}

void ConfigOptionReader::VisitString(const std::string& key, std::string* value,
                                     const std::string&) {
  *value = section_.GetString(key, *value);
}

void ConfigOptionReader::VisitChoice(const std::string& key, int* index,
                                     const std::vector<std::string>& names,
                                     const std::string&) {
  if (!section_.Has(key)) return;
  const std::string name = section_.GetString(key, "");
  for (size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) {
      *index = static_cast<int>(k);
      return;
    }
  }
  std::string expected;
  for (size_t k = 0; k < names.size(); ++k) {
    expected += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  section_.FailKey(key, "expected " + expected + ", got '" + name + "'");
}

void ConfigOptionReader::VisitDoubleList(const std::string& key,
                                         const std::vector<double*>& values,
                                         const std::vector<OptionUnit>& units,
                                         const std::string& layout, const std::string&) {
  if (!section_.Has(key)) return;
  const std::vector<double> list = section_.GetDoubles(key, {});
  if (list.size() != values.size()) section_.FailKey(key, "expected " + layout);
  for (size_t k = 0; k < values.size(); ++k) *values[k] = FromConfigUnit(list[k], units[k]);
}

void FailOptionsProblem(const Config& section, const std::string& problem) {
  const size_t end = problem.find_first_of(" =:");
  const std::string key = problem.substr(0, end);
  if (end != std::string::npos && section.Has(key)) {
    size_t rest = problem.find_first_not_of(" =:", end);
    // "KEY = VALUE: must be ..." reads "KEY: must be ..., got VALUE" at the key's line.
    if (problem.compare(end, 3, " = ") == 0) {
      const size_t colon = problem.find(": ", end);
      if (colon != std::string::npos) {
        section.FailKey(key, problem.substr(colon + 2) + ", got " +
                                 problem.substr(end + 3, colon - end - 3));
      }
    }
    section.FailKey(key, problem.substr(rest == std::string::npos ? problem.size() : rest));
  }
  section.Fail(problem);
}

void RejectRenamedKeys(const Config& section, const std::vector<RenamedKey>& renamed,
                       const std::string& documented_in) {
  for (const RenamedKey& r : renamed) {
    if (section.Has(r.old_key)) {
      section.FailKey(r.old_key, "renamed to " + r.new_key + " (" + documented_in + ")");
    }
  }
}

}  // namespace slammtt
