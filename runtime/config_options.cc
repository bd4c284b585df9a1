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

void RejectRenamedKeys(const Config& section, const std::vector<RenamedKey>& renamed,
                       const std::string& documented_in) {
  for (const RenamedKey& r : renamed) {
    if (section.Has(r.old_key)) {
      section.FailKey(r.old_key, "renamed to " + r.new_key + " (" + documented_in + ")");
    }
  }
}

}  // namespace slammtt
