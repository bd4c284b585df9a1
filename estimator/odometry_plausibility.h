// Physical plausibility of ODOMETRY readings: what a Pioneer P3-DX base can report.
//
// A reading is implausible, and rejected, when
//  - its pose or velocities are not finite;
//  - |x| or |y| exceeds max_coordinate_m (beyond any world the base can drive in), or the
//    heading's magnitude exceeds kMaxOdometryHeading_rad (no angle is left in a double there);
//  - |linear_mps| exceeds max_speed_mps or |angular_radps| exceeds max_turn_rate_radps;
//  - against the last accepted reading, dt seconds earlier, it moved farther than
//    max_speed_mps * (dt + time_jitter_s) or turned (wrapped) by more than
//    max_turn_rate_radps * (dt + time_jitter_s): a jump no base can make. time_jitter_s covers
//    stamps taken on arrival (the P3-DX sends a SIP every 100 ms; one late SIP makes the next
//    interval look short).
// One implausible reading is never believed, however it looks. But the odometry frame can jump
// for real (a driver or base restarted and its integrated pose began again at zero): when
// `confirm_readings` readings in a row pass the first three checks, are each plausible against
// the one before, and all fail against the last accepted one, the last of them is kNewFrame: the
// caller re-anchors the odometry there (the motion across the jump is unknown).
//
// Defaults (EstimatorOptions::odometry_check): well beyond what the base can do, so that noise
// never trips them. The Pioneer 3-DX datasheet (Adept MobileRobots, 2011) gives a maximum
// speed of 1.2 m/s, rotation 300 deg/s and 8-10 h of run time on three batteries; the paper's
// simulated robot (scenario s1-crossing) drives at up to 2 m/s, its noisy odometry reports
// 2.017 m/s. Bounds: 3 m/s, 600 deg/s, 1e5 m (more than 10 h at 3 m/s, 1.1e5 m, would need
// wrap-free counters no P3-DX has; a real run stays far inside).
#pragma once

#include <cmath>
#include <string>

#include "common/options_schema.h"
#include "estimator/odometry_buffer.h"

namespace slammtt {

// Beyond this, a heading is no angle: the spacing of doubles there exceeds 1e-6 rad.
inline constexpr double kMaxOdometryHeading_rad = 1e9;

struct OdometryPlausibilityOptions {
  double max_speed_mps = 3.0;
  double max_turn_rate_radps = 600.0 * M_PI / 180.0;
  double time_jitter_s = 0.1;
  double max_coordinate_m = 1e5;
};

// The schema of these options (keys in EstimatorOptions' group `odometry_check`).
void VisitOdometryPlausibilityOptions(OptionVisitor* visitor,
                                      OdometryPlausibilityOptions* options);

enum class OdometryVerdict { kPlausible, kImplausible, kNewFrame };

class OdometryPlausibility {
 public:
  // The verdict on one reading; `why` (when not null) gets one line for an implausible one.
  // kPlausible and kNewFrame readings become the reference of the next.
  OdometryVerdict Judge(const OdometryReading& reading, const OdometryPlausibilityOptions& options,
                        int confirm_readings, std::string* why);

  // Forgets the reference (the estimation started over).
  void Reset();

 private:
  bool has_reference_ = false;
  OdometryReading reference_;
  int run_length_ = 0;        // implausible-but-consistent readings in a row
  OdometryReading run_last_;
};

// The first three checks above alone (no reference): "" when the reading passes, else why not.
std::string OdometryReadingProblem(const OdometryReading& reading,
                                   const OdometryPlausibilityOptions& options);

// The jump check: "" when `later` can follow `earlier`, else why not.
std::string OdometryJumpProblem(const OdometryReading& earlier, const OdometryReading& later,
                                const OdometryPlausibilityOptions& options);

}  // namespace slammtt
