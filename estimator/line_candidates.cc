#include "estimator/line_candidates.h"

#include <algorithm>
#include <cmath>

#include "common/angle.h"
#include "estimator/line_landmarks.h"

namespace slammtt {

void DropStaleLineCandidates(int64_t utime, const LineLandmarkOptions& options,
                             std::vector<LineCandidate>* candidates) {
  candidates->erase(std::remove_if(candidates->begin(), candidates->end(),
                                   [&](const LineCandidate& c) {
                                     return static_cast<double>(utime - c.last_seen_utime) *
                                                1e-6 >
                                            options.candidate_timeout_s;
                                   }),
                    candidates->end());
}

bool ContinuesLineCandidate(const LineCandidate& seen, const LineCandidate& candidate,
                            const LineLandmarkOptions& options) {
  double sign = 1.0;
  double angle = WrapAngle(seen.line(1) - candidate.line(1));
  if (std::abs(angle) > 0.5 * M_PI) {
    sign = -1.0;  // the same line written as (-rho, alpha + pi)
    angle = WrapAngle(angle + M_PI);
  }
  if (std::abs(angle) > options.candidate_match_rad ||
      std::abs(sign * seen.line(0) - candidate.line(0)) > options.candidate_match_m) {
    return false;
  }
  // The seen extent in the candidate's coordinates (the direction flips with the sign).
  const double from = sign > 0.0 ? seen.extent_from_m : -seen.extent_to_m;
  const double to = sign > 0.0 ? seen.extent_to_m : -seen.extent_from_m;
  return from <= candidate.extent_to_m + options.extent_gap_m &&
         to >= candidate.extent_from_m - options.extent_gap_m;
}

bool ConfirmLineCandidate(const LineCandidate& seen, const LineLandmarkOptions& options,
                          std::vector<LineCandidate>* candidates) {
  const int64_t utime = seen.last_seen_utime;
  auto continued = std::find_if(
      candidates->begin(), candidates->end(), [&](const LineCandidate& c) {
        return c.last_seen_utime < utime && ContinuesLineCandidate(seen, c, options);
      });
  if (continued == candidates->end()) {
    candidates->push_back(seen);
    continued = candidates->end() - 1;
  } else {
    continued->scans += 1;
    continued->line = seen.line;
    continued->last_seen_utime = utime;
    continued->extent_from_m = seen.extent_from_m;
    continued->extent_to_m = seen.extent_to_m;
  }
  if (continued->scans < options.confirm_scans) return false;
  candidates->erase(continued);
  return true;
}

}  // namespace slammtt
