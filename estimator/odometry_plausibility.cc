#include "estimator/odometry_plausibility.h"

#include <algorithm>
#include <sstream>

#include "common/angle.h"
#include "common/utime.h"

namespace slammtt {

void VisitOdometryPlausibilityOptions(OptionVisitor* v, OdometryPlausibilityOptions* o) {
  using R = OptionRange;
  v->Double("max_speed_mps", &o->max_speed_mps, R::Above(0),
            "faster odometry is rejected (P3-DX datasheet: 1.2 m/s; s1 robot: 2 m/s)");
  v->Double("max_turn_rate_radps", &o->max_turn_rate_radps, R::Above(0),
            "faster-turning odometry is rejected (P3-DX datasheet: 300 deg/s)",
            OptionUnit::kDegrees);
  v->Double("time_jitter_s", &o->time_jitter_s, R::AtLeast(0),
            "stamp jitter allowed for in the jump check (one 100 ms SIP cycle)");
  v->Double("max_coordinate_m", &o->max_coordinate_m, R::Above(0),
            "odometry x or y beyond this is rejected");
}

std::string OdometryReadingProblem(const OdometryReading& r,
                                   const OdometryPlausibilityOptions& o) {
  std::ostringstream why;
  if (!r.pose.allFinite() || !std::isfinite(r.linear_mps) || !std::isfinite(r.angular_radps)) {
    why << "not finite";
  } else if (std::max(std::abs(r.pose(0)), std::abs(r.pose(1))) > o.max_coordinate_m) {
    why << "position (" << r.pose(0) << ", " << r.pose(1) << ") m beyond "
        << o.max_coordinate_m << " m";
  } else if (std::abs(r.pose(2)) > kMaxOdometryHeading_rad) {
    why << "heading " << r.pose(2) << " rad is no angle";
  } else if (std::abs(r.linear_mps) > o.max_speed_mps) {
    why << "speed " << r.linear_mps << " m/s beyond " << o.max_speed_mps << " m/s";
  } else if (std::abs(r.angular_radps) > o.max_turn_rate_radps) {
    why << "turn rate " << r.angular_radps << " rad/s beyond " << o.max_turn_rate_radps
        << " rad/s";
  }
  return why.str();
}

std::string OdometryJumpProblem(const OdometryReading& earlier, const OdometryReading& later,
                                const OdometryPlausibilityOptions& o) {
  const double dt_s = std::max(0.0, SecondsBetween(later.utime, earlier.utime));
  const double allowed_s = dt_s + o.time_jitter_s;
  const double moved_m = (later.pose.head<2>() - earlier.pose.head<2>()).norm();
  const double turned_rad = std::abs(WrapAngle(later.pose(2) - earlier.pose(2)));
  std::ostringstream why;
  if (!(moved_m <= o.max_speed_mps * allowed_s)) {
    why << "moved " << moved_m << " m in " << dt_s << " s (at most " << o.max_speed_mps
        << " m/s)";
  } else if (!(turned_rad <= o.max_turn_rate_radps * allowed_s)) {
    why << "turned " << turned_rad << " rad in " << dt_s << " s (at most "
        << o.max_turn_rate_radps << " rad/s)";
  }
  return why.str();
}

OdometryVerdict OdometryPlausibility::Judge(const OdometryReading& reading,
                                            const OdometryPlausibilityOptions& options,
                                            int confirm_readings, std::string* why) {
  std::string problem = OdometryReadingProblem(reading, options);
  if (problem.empty() && has_reference_) {
    problem = OdometryJumpProblem(reference_, reading, options);
    if (!problem.empty()) {
      // Implausible against the reference: is it the start, or the next, of a jumped frame?
      const bool continues_run =
          run_length_ > 0 && OdometryJumpProblem(run_last_, reading, options).empty();
      run_length_ = continues_run ? run_length_ + 1 : 1;
      run_last_ = reading;
      if (run_length_ >= confirm_readings) {
        reference_ = reading;
        run_length_ = 0;
        return OdometryVerdict::kNewFrame;
      }
    }
  }
  if (!problem.empty()) {
    if (why != nullptr) *why = problem;
    return OdometryVerdict::kImplausible;
  }
  has_reference_ = true;
  reference_ = reading;
  run_length_ = 0;
  return OdometryVerdict::kPlausible;
}

void OdometryPlausibility::Reset() {
  has_reference_ = false;
  run_length_ = 0;
}

}  // namespace slammtt
