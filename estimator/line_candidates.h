// Step 1b.6 of a scan (line_landmarks.h): a line feature that starts no landmark at once. A
// feature in no pair and outside gate dn of every landmark is a candidate line, kept outside the
// state: it becomes a line landmark only when it is seen again, in lines_confirm_scans scans
// with no gap longer than lines_candidate_timeout_s. A straight run that does not stay (people
// walking side by side, a cluster that happens to be straight in one scan) never enters the
// state, so a scene without walls is estimated exactly as without line landmarks.
//
// A later feature continues a candidate when both are the same line of the map frame within
// lines_candidate_match_m and lines_candidate_match_deg (either sign of (rho, alpha): the same
// line is (rho, alpha) and (-rho, alpha + pi)) and their extents overlap or lie within
// lines_extent_gap_m. The candidate then takes the feature's line and extent (the latest
// sighting, placed by the latest pose).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace slammtt {

struct LineLandmarkOptions;  // line_landmarks.h

// A straight run seen in recent scans that is not a landmark yet, in the map frame.
struct LineCandidate {
  Eigen::Vector2d line = Eigen::Vector2d::Zero();  // (rho, alpha), from its latest feature
  double extent_from_m = 0.0;                       // along the line, as LineRecord's
  double extent_to_m = 0.0;
  int scans = 0;                                    // scans it was seen in
  int64_t first_seen_utime = 0;
  int64_t last_seen_utime = 0;
};

// Drops the candidates unseen for longer than options.candidate_timeout_s at `utime`.
void DropStaleLineCandidates(int64_t utime, const LineLandmarkOptions& options,
                             std::vector<LineCandidate>* candidates);

// Whether `seen` (one feature's line, extent and time) continues `candidate` (above).
bool ContinuesLineCandidate(const LineCandidate& seen, const LineCandidate& candidate,
                            const LineLandmarkOptions& options);

// Records the sighting `seen` (seen.scans = 1, seen at seen.last_seen_utime): it continues the
// first candidate it continues that was not seen at that utime yet, or starts a new candidate.
// Returns true when that candidate has now been seen in options.confirm_scans scans: it is
// taken out of `candidates`, and the caller makes the feature a landmark (or refuses it).
bool ConfirmLineCandidate(const LineCandidate& seen, const LineLandmarkOptions& options,
                          std::vector<LineCandidate>* candidates);

}  // namespace slammtt
