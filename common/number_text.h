// Numbers written as text by people: command-line values, recorded-trajectory files, fault
// schedules of the emulators. The whole text must be the number, so "2.5x", "" and "1e999" are
// mistakes to report, not 2.5, 0 and infinity. Header-only, standard library only (like
// everything in common/).
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

namespace slammtt {

// The finite double that the whole of `text` spells, in strtod's syntax (C11 7.22.1.3: decimal
// or hexadecimal, optional sign and exponent; leading white space is skipped). nullopt for an
// empty text, anything after the number, NaN, an infinity, or a value out of double's range
// (ERANGE, overflow and underflow alike).
inline std::optional<double> ParseFiniteDouble(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// The base-10 whole number that the whole of `text` spells (strtoll's syntax: optional sign,
// leading white space skipped). nullopt for an empty text, anything after the number, or a
// value beyond int64_t.
inline std::optional<int64_t> ParseWholeNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return std::nullopt;
  return static_cast<int64_t>(value);
}

}  // namespace slammtt
