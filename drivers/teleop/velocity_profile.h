// A scripted drive for slammtt-teleop --profile FILE: one constant command per line,
//   duration_s linear_mps angular_radps
// held for duration_s, in file order; '#' starts a comment, blank lines are skipped. After the
// last line the robot stops. Pure: text in, steps out.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace slammtt {

struct VelocityProfileStep {
  double duration_s = 0.0;
  double linear_mps = 0.0;
  double angular_radps = 0.0;
  int line = 0;  // 1-based line of the file
};

// Bounds of a profile line: up to an hour per step, speeds well beyond any base (the driver
// clamps to its own limits: p3dx.max_linear_mps, max_angular_radps).
inline constexpr double kMaxProfileStepS = 3600.0;
inline constexpr double kMaxProfileLinearMps = 5.0;
inline constexpr double kMaxProfileAngularRadps = 10.0;

// Parses a profile. std::invalid_argument with one line "SOURCE:LINE: what is wrong" for a line
// that is not three finite numbers within the bounds (duration > 0), and "SOURCE: no steps" for
// a profile without any.
std::vector<VelocityProfileStep> ParseVelocityProfile(const std::string& text,
                                                      const std::string& source);

// The step in force `elapsed_s` after the start (steps back to back), nullopt after the last.
std::optional<VelocityProfileStep> ProfileStepAt(const std::vector<VelocityProfileStep>& steps,
                                                 double elapsed_s);

// The sum of the steps' durations.
double ProfileDurationS(const std::vector<VelocityProfileStep>& steps);

}  // namespace slammtt
