#include "drivers/common/fault_schedule.h"

#include <optional>
#include <stdexcept>
#include <utility>

#include "common/number_text.h"

namespace slammtt {

double FaultNumber(const std::string& argument, double fallback, const std::string& text) {
  if (argument.empty()) return fallback;
  const std::optional<double> value = ParseFiniteDouble(argument);
  if (!value || *value < 0.0 || *value > 1e6) {
    throw std::invalid_argument("fault '" + text + "': '" + argument +
                                "' is not a number from 0 to 1000000");
  }
  return *value;
}

ScheduledFault ParseScheduledFault(const std::string& text,
                                   const std::vector<std::string>& kinds) {
  const size_t at = text.find('@');
  if (at == std::string::npos) {
    throw std::invalid_argument("fault '" + text + "': expected KIND@SECONDS[:ARG]");
  }
  ScheduledFault fault;
  fault.kind = text.substr(0, at);
  bool known = false;
  std::string names;
  for (const std::string& kind : kinds) {
    known = known || kind == fault.kind;
    names += (names.empty() ? "" : ", ") + kind;
  }
  if (!known) {
    throw std::invalid_argument("fault '" + text + "': unknown kind '" + fault.kind + "' (" +
                                names + ")");
  }
  const std::string rest = text.substr(at + 1);
  const size_t colon = rest.find(':');
  const std::string when = rest.substr(0, colon);
  if (when.empty()) throw std::invalid_argument("fault '" + text + "': missing the time in seconds");
  fault.at_s = FaultNumber(when, 0.0, text);
  if (colon != std::string::npos) fault.argument = rest.substr(colon + 1);
  return fault;
}

FaultSchedule::FaultSchedule(std::vector<double> at_s)
    : at_s_(std::move(at_s)), fired_(at_s_.size(), false), pending_(at_s_.size()) {}

std::vector<size_t> FaultSchedule::TakeDue(double elapsed_s) {
  std::vector<size_t> due;
  for (size_t i = 0; i < at_s_.size(); ++i) {
    if (fired_[i] || elapsed_s < at_s_[i]) continue;
    fired_[i] = true;
    --pending_;
    due.push_back(i);
  }
  return due;
}

}  // namespace slammtt
