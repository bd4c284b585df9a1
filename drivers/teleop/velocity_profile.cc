#include "drivers/teleop/velocity_profile.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/number_text.h"

namespace slammtt {

namespace {

std::vector<std::string> Words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

}  // namespace

std::vector<VelocityProfileStep> ParseVelocityProfile(const std::string& text,
                                                      const std::string& source) {
  std::vector<VelocityProfileStep> steps;
  std::istringstream in(text);
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> words = Words(line);
    if (words.empty()) continue;
    const auto fail = [&](const std::string& what) {
      throw std::invalid_argument(source + ":" + std::to_string(line_number) + ": " + what);
    };
    if (words.size() != 3) {
      fail("expected 'duration_s linear_mps angular_radps', got " +
           std::to_string(words.size()) + " fields");
    }
    double values[3] = {0.0, 0.0, 0.0};
    for (size_t i = 0; i < 3; ++i) {
      const std::optional<double> value = ParseFiniteDouble(words[i]);
      if (!value) fail("'" + words[i] + "' is not a finite number");
      values[i] = *value;
    }
    if (!(values[0] > 0.0 && values[0] <= kMaxProfileStepS)) {
      fail("duration_s must be in (0, 3600], got " + words[0]);
    }
    if (std::abs(values[1]) > kMaxProfileLinearMps) {
      fail("|linear_mps| must be at most 5, got " + words[1]);
    }
    if (std::abs(values[2]) > kMaxProfileAngularRadps) {
      fail("|angular_radps| must be at most 10, got " + words[2]);
    }
    steps.push_back(VelocityProfileStep{values[0], values[1], values[2], line_number});
  }
  if (steps.empty()) throw std::invalid_argument(source + ": no steps");
  return steps;
}

std::optional<VelocityProfileStep> ProfileStepAt(const std::vector<VelocityProfileStep>& steps,
                                                 double elapsed_s) {
  double end_s = 0.0;
  for (const VelocityProfileStep& step : steps) {
    end_s += step.duration_s;
    if (elapsed_s < end_s) return step;
  }
  return std::nullopt;
}

double ProfileDurationS(const std::vector<VelocityProfileStep>& steps) {
  double total_s = 0.0;
  for (const VelocityProfileStep& step : steps) total_s += step.duration_s;
  return total_s;
}

}  // namespace slammtt
