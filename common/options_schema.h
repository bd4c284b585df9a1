// Options schemas: each module lists every option once (its field, valid range, unit and a
// one-line doc) in a function that shows each field to an OptionVisitor, and the configuration
// reader, the validation and the documentation table are visitors of that one list (Drake's
// Serialize(Archive*) idea: docs/DEVELOPING.md, "Options"). Header-only, standard library only,
// so pure libraries may declare their schema here; the YAML reader lives in runtime/
// (runtime/config_options.h).
//
// Keys. An option's configuration key is its field's name, with the name of the struct it sits
// in (BeginGroup) and '_' in front for a field of a nested struct (`tracks.confirm_hits` is
// `tracks_confirm_hits`). A field in radians (name ending in `_rad` or `_radps`, unit
// kDegrees) is written in degrees, and its key says so: `field_of_view_rad` is read as
// `field_of_view_deg`, `gap_robot_heading_sigma_radps` as `gap_robot_heading_sigma_degps`.
// Ranges are given in the unit of the configuration (degrees for kDegrees).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace slammtt {

// How the configuration writes a field.
enum class OptionUnit {
  kAsIs,     // as the field holds it
  kDegrees,  // the field holds radians (or rad/s), the configuration degrees (or deg/s)
};

// A field's value in the unit of the configuration, and back. Degrees: x * 180 / pi and
// x * pi / 180, in that order of operations (the conversion every reader of the project uses).
inline double ToConfigUnit(double field_value, OptionUnit unit) {
  return unit == OptionUnit::kDegrees ? field_value * 180.0 / M_PI : field_value;
}
inline double FromConfigUnit(double config_value, OptionUnit unit) {
  return unit == OptionUnit::kDegrees ? config_value * M_PI / 180.0 : config_value;
}

// The values an option may take, in the unit of the configuration: an interval whose ends are
// included or not; non-finite values are never valid.
struct OptionRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_included = true;
  bool max_included = true;

  static OptionRange Any() { return OptionRange(); }
  static OptionRange AtLeast(double lo) { return {lo, kInfinity, true, true}; }
  static OptionRange Above(double lo) { return {lo, kInfinity, false, true}; }
  static OptionRange Between(double lo, double hi) { return {lo, hi, true, true}; }
  static OptionRange AboveUpTo(double lo, double hi) { return {lo, hi, false, true}; }
  static OptionRange Open(double lo, double hi) { return {lo, hi, false, false}; }

  bool Contains(double value) const {
    if (!std::isfinite(value)) return false;
    if (min_included ? value < min : value <= min) return false;
    if (max_included ? value > max : value >= max) return false;
    return true;
  }
  // "any", ">= 0", "> 0", "[1, 4096]", "(0, 360]", "(0, 1)".
  std::string Text() const {
    const bool has_min = std::isfinite(min);
    const bool has_max = std::isfinite(max);
    if (!has_min && !has_max) return "any";
    if (!has_max) return std::string(min_included ? ">= " : "> ") + Number(min);
    if (!has_min) return std::string(max_included ? "<= " : "< ") + Number(max);
    return std::string(min_included ? "[" : "(") + Number(min) + ", " + Number(max) +
           (max_included ? "]" : ")");
  }
  // What a value must be, for messages: "in [1, 1000]", "in (0, 360]", ">= 0", "> 0".
  std::string Requirement() const {
    const std::string text = Text();
    return text[0] == '[' || text[0] == '(' ? "in " + text : text;
  }
  // A number as the documentation and messages print it (6 significant digits).
  static std::string Number(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
  }

 private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
};

// What a schema shows each option to. The schema function calls the public methods with the
// field's name (not the key) and a pointer to the field; a visitor reads it, writes it or both.
// Subclasses implement the Visit* methods, which get the key.
class OptionVisitor {
 public:
  virtual ~OptionVisitor() = default;

  // The fields of a nested struct `field` follow, until EndGroup().
  void BeginGroup(const std::string& field) { groups_.push_back(field); }
  void EndGroup() { groups_.pop_back(); }

  void Double(const std::string& field, double* value, const OptionRange& range,
              const std::string& doc, OptionUnit unit = OptionUnit::kAsIs) {
    VisitDouble(KeyOf(field, unit), value, range, unit, doc);
  }
  void Int(const std::string& field, int64_t* value, const OptionRange& range,
           const std::string& doc) {
    VisitInt(KeyOf(field, OptionUnit::kAsIs), value, range, doc);
  }
  // An int field, through an int64_t (ranges keep it within int).
  void Int(const std::string& field, int* value, const OptionRange& range,
           const std::string& doc) {
    int64_t wide = *value;
    Int(field, &wide, range, doc);
    *value = static_cast<int>(wide);
  }
  void Bool(const std::string& field, bool* value, const std::string& doc) {
    VisitBool(KeyOf(field, OptionUnit::kAsIs), value, doc);
  }
  // A text (a device path, a file name); what makes it valid is the module's check.
  void String(const std::string& field, std::string* value, const std::string& doc) {
    VisitString(KeyOf(field, OptionUnit::kAsIs), value, doc);
  }
  // An enumeration written as one of `names`; *index is the position of its name.
  void Choice(const std::string& field, int* index, const std::vector<std::string>& names,
              const std::string& doc) {
    VisitChoice(KeyOf(field, OptionUnit::kAsIs), index, names, doc);
  }
  // A fixed-length list of numbers written [a, b, ...], each with its unit; `layout` names the
  // elements for the documentation and messages ("[x_m, y_m, heading_deg]").
  void DoubleList(const std::string& field, const std::vector<double*>& values,
                  const std::vector<OptionUnit>& units, const std::string& layout,
                  const std::string& doc) {
    VisitDoubleList(KeyOf(field, OptionUnit::kAsIs), values, units, layout, doc);
  }

  // The configuration key of `field` in the current group (see the top of this file).
  std::string KeyOf(const std::string& field, OptionUnit unit) const {
    std::string key;
    for (const std::string& group : groups_) key += group + "_";
    if (unit == OptionUnit::kDegrees) {
      for (const auto& [radians, degrees] :
           {std::pair<std::string, std::string>("_radps", "_degps"), {"_rad", "_deg"}}) {
        if (field.size() > radians.size() &&
            field.compare(field.size() - radians.size(), radians.size(), radians) == 0) {
          return key + field.substr(0, field.size() - radians.size()) + degrees;
        }
      }
    }
    return key + field;
  }

 protected:
  virtual void VisitDouble(const std::string& key, double* value, const OptionRange& range,
                           OptionUnit unit, const std::string& doc) = 0;
  virtual void VisitInt(const std::string& key, int64_t* value, const OptionRange& range,
                        const std::string& doc) = 0;
  virtual void VisitBool(const std::string& key, bool* value, const std::string& doc) = 0;
  virtual void VisitString(const std::string& key, std::string* value,
                           const std::string& doc) = 0;
  virtual void VisitChoice(const std::string& key, int* index,
                           const std::vector<std::string>& names, const std::string& doc) = 0;
  virtual void VisitDoubleList(const std::string& key, const std::vector<double*>& values,
                               const std::vector<OptionUnit>& units, const std::string& layout,
                               const std::string& doc) = 0;

 private:
  std::vector<std::string> groups_;
};

// The validation visitor: the first option whose value lies outside its range, as one line
// naming its key ("" when every value is valid). Values are judged in the unit of the
// configuration.
class OptionRangeCheck : public OptionVisitor {
 public:
  const std::string& problem() const { return problem_; }
  // The same problem in two parts, for a caller that names the key its own way (a scenario's
  // "laser.fov_deg"): the key, and what is wrong ("must be in (0, 360], got 400").
  const std::string& problem_key() const { return problem_key_; }
  const std::string& problem_detail() const { return problem_detail_; }

 protected:
  void VisitDouble(const std::string& key, double* value, const OptionRange& range,
                   OptionUnit unit, const std::string&) override {
    Check(key, ToConfigUnit(*value, unit), range);
  }
  void VisitInt(const std::string& key, int64_t* value, const OptionRange& range,
                const std::string&) override {
    Check(key, static_cast<double>(*value), range);
  }
  void VisitBool(const std::string&, bool*, const std::string&) override {}
  void VisitString(const std::string&, std::string*, const std::string&) override {}
  void VisitChoice(const std::string& key, int* index, const std::vector<std::string>& names,
                   const std::string&) override {
    if (*index < 0 || static_cast<size_t>(*index) >= names.size()) {
      Report(key, key + " is not one of its choices", "is not one of its choices");
    }
  }
  void VisitDoubleList(const std::string& key, const std::vector<double*>& values,
                       const std::vector<OptionUnit>&, const std::string& layout,
                       const std::string&) override {
    for (const double* value : values) {
      if (!std::isfinite(*value)) {
        Report(key, key + " must be finite " + layout, "must be finite " + layout);
      }
    }
  }

 private:
  void Check(const std::string& key, double value, const OptionRange& range) {
    if (!range.Contains(value)) {
      const std::string number = OptionRange::Number(value);
      Report(key, key + " = " + number + ": must be " + range.Requirement(),
             "must be " + range.Requirement() + ", got " + number);
    }
  }
  void Report(const std::string& key, const std::string& problem, const std::string& detail) {
    if (!problem_.empty()) return;
    problem_ = problem;
    problem_key_ = key;
    problem_detail_ = detail;
  }
  std::string problem_;
  std::string problem_key_;
  std::string problem_detail_;
};

// The documentation visitor: one Markdown table row per option, | key | default | valid |
// what |, defaults and ranges in the unit of the configuration.
class OptionsMarkdownTable : public OptionVisitor {
 public:
  std::string Table() const {
    return "| key | default | valid | what |\n|---|---|---|---|\n" + rows_;
  }

 protected:
  void VisitDouble(const std::string& key, double* value, const OptionRange& range,
                   OptionUnit unit, const std::string& doc) override {
    Row(key, OptionRange::Number(ToConfigUnit(*value, unit)), range.Text(), doc);
  }
  void VisitInt(const std::string& key, int64_t* value, const OptionRange& range,
                const std::string& doc) override {
    Row(key, std::to_string(*value), range.Text(), doc);
  }
  void VisitBool(const std::string& key, bool* value, const std::string& doc) override {
    Row(key, *value ? "true" : "false", "true, false", doc);
  }
  void VisitString(const std::string& key, std::string* value, const std::string& doc) override {
    Row(key, value->empty() ? "\"\"" : *value, "text", doc);
  }
  void VisitChoice(const std::string& key, int* index, const std::vector<std::string>& names,
                   const std::string& doc) override {
    std::string all;
    for (const std::string& name : names) all += (all.empty() ? "" : ", ") + name;
    Row(key, names[static_cast<size_t>(*index)], all, doc);
  }
  void VisitDoubleList(const std::string& key, const std::vector<double*>& values,
                       const std::vector<OptionUnit>& units, const std::string& layout,
                       const std::string& doc) override {
    std::string list;
    for (size_t k = 0; k < values.size(); ++k) {
      list += (k == 0 ? "[" : ", ") + OptionRange::Number(ToConfigUnit(*values[k], units[k]));
    }
    Row(key, list + "]", layout, doc);
  }

 private:
  void Row(const std::string& key, const std::string& value, const std::string& valid,
           const std::string& doc) {
    rows_ += "| `" + key + "` | " + value + " | " + valid + " | " + doc + " |\n";
  }
  std::string rows_;
};

}  // namespace slammtt
